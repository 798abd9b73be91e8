// Declared plugin options: the loader's checks of a declaration, value normalisation per type, and the
// resolution of scene and command-line requests against the declarations.
#include "loader/plugin_options.hpp"

#include <gtest/gtest.h>

namespace nimbus {
namespace plugin_options_test {

const char *const kModes[] = {"fast", "exact", nullptr};

struct Declared {
  std::vector<nimbus_option_decl_t> decls;
  nimbus_option_list_t list{};
  nimbus_descriptor_t desc{};
  explicit Declared(std::vector<nimbus_option_decl_t> d) : decls(std::move(d)) {
    list = {{sizeof(nimbus_option_list_t), NIMBUS_S_TYPE_OPTION_LIST, nullptr},
            uint32_t(decls.size()),
            0,
            decls.data()};
    desc.header = {sizeof(nimbus_descriptor_t), NIMBUS_S_TYPE_DESCRIPTOR, &list};
  }
};

std::vector<nimbus_option_decl_t> good() {
  return {{"caustics", NIMBUS_OPTION_SWITCH, 0, "on", nullptr, "the switch"},
          {"mode", NIMBUS_OPTION_CHOICE, 0, "fast", kModes, "how"},
          {"count", NIMBUS_OPTION_INT, 0, "16", nullptr, "how many"},
          {"scale", NIMBUS_OPTION_FLOAT, 0, "0.5", nullptr, "how much"},
          {"label", NIMBUS_OPTION_STRING, 0, "", nullptr, "a name"}};
}

TEST(PluginOptions, ReadsEveryDeclarationWithItsDefault) {
  Declared d(good());
  const auto decls = read_option_declarations(d.desc);
  ASSERT_TRUE(decls.ok()) << decls.error().message;
  ASSERT_EQ(decls->size(), 5u);
  EXPECT_EQ((*decls)[0].name, "caustics");
  EXPECT_EQ((*decls)[0].default_value, "on");
  EXPECT_EQ((*decls)[1].allowed, (std::vector<std::string>{"fast", "exact"}));
  EXPECT_EQ((*decls)[2].default_value, "16");
}

TEST(PluginOptions, NoListMeansNoOptionsAndUnknownAddOnsAreSkipped) {
  nimbus_descriptor_t desc{};
  desc.header = {sizeof(desc), NIMBUS_S_TYPE_DESCRIPTOR, nullptr};
  EXPECT_TRUE(read_option_declarations(desc)->empty());
  const nimbus_struct_header_t unknown{sizeof(nimbus_struct_header_t), 999u, nullptr};
  desc.header.next = &unknown;
  EXPECT_TRUE(read_option_declarations(desc)->empty());
}

TEST(PluginOptions, BadDeclarationsAreRefusedWithTheReason) {
  const auto refused = [](nimbus_option_decl_t o, const std::string &reason) {
    Declared d({o});
    const auto r = read_option_declarations(d.desc);
    ASSERT_FALSE(r.ok()) << o.name;
    EXPECT_NE(r.error().message.find(reason), std::string::npos) << r.error().message;
  };
  refused({"Bad", NIMBUS_OPTION_SWITCH, 0, "on", nullptr, ""}, "invalid name");
  refused({"x", 77u, 0, "on", nullptr, ""}, "unknown type");
  refused({"x", NIMBUS_OPTION_CHOICE, 0, "a", nullptr, ""}, "no allowed values");
  refused({"x", NIMBUS_OPTION_CHOICE, 0, "slow", kModes, ""}, "default 'slow'");
  refused({"x", NIMBUS_OPTION_SWITCH, 0, "maybe", nullptr, ""}, "default 'maybe'");
  refused({"x", NIMBUS_OPTION_INT, 0, "1.5", nullptr, ""}, "default '1.5'");
  Declared twice(
      {{"x", NIMBUS_OPTION_SWITCH, 0, "on", nullptr, ""}, {"x", NIMBUS_OPTION_SWITCH, 0, "on", nullptr, ""}});
  EXPECT_FALSE(read_option_declarations(twice.desc).ok());
}

TEST(PluginOptions, ValuesAreNormalisedPerType) {
  Declared d(good());
  const auto decls = *read_option_declarations(d.desc);
  EXPECT_EQ(normalize_option_value(decls[0], "TRUE"), "on");
  EXPECT_EQ(normalize_option_value(decls[0], "no"), "off");
  EXPECT_FALSE(normalize_option_value(decls[0], "maybe"));
  EXPECT_EQ(normalize_option_value(decls[1], "exact"), "exact");
  EXPECT_FALSE(normalize_option_value(decls[1], "Exact"));
  EXPECT_EQ(normalize_option_value(decls[2], "-3"), "-3");
  EXPECT_FALSE(normalize_option_value(decls[2], "3x"));
  EXPECT_FALSE(normalize_option_value(decls[3], "inf"));
  EXPECT_EQ(normalize_option_value(decls[3], "1e-3"), "1e-3");
  EXPECT_EQ(normalize_option_value(decls[4], "any text"), "any text");
}

TEST(PluginOptions, ResolutionGivesEveryOptionAndLaterRequestsWin) {
  Declared d(good());
  const auto decls = *read_option_declarations(d.desc);
  const auto r = resolve_options("org.test", decls,
                                 {{"caustics", "off", "scene.yaml:3:5"}, {"caustics", "yes", "--caustics"}});
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_EQ(r->size(), 5u);
  EXPECT_EQ((*r)[0], (std::pair<std::string, std::string>{"caustics", "on"}));
  EXPECT_EQ((*r)[1].second, "fast");
}

TEST(PluginOptions, UnknownOptionsAndBadValuesNameWhereAndThePlugin) {
  Declared d(good());
  const auto decls = *read_option_declarations(d.desc);
  const auto unknown =
      resolve_options("org.test", decls, {{"photons", "9", "scene.yaml:7:3: render.photons"}});
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(
      unknown.error().message,
      "scene.yaml:7:3: render.photons: org.test has no option 'photons' (its options: caustics, mode, count, "
      "scale, label)");
  const auto bad = resolve_options("org.test", decls, {{"mode", "slow", "--mode"}});
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().message, "--mode: org.test option 'mode' expects fast|exact, got 'slow'");
  const auto none = resolve_options("nimbus.pt", {}, {{"caustics", "on", "--caustics"}});
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.error().message.find("nimbus.pt has no option 'caustics' (it declares no options)"),
            std::string::npos);
}

}  // namespace plugin_options_test
}  // namespace nimbus
