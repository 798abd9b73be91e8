// Discovery against fixture plugins: what loads, what is refused with which exact line, and which library
// functions the host called on the way (the fixtures' marker logs).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "plugin_test_support.hpp"

namespace nimbus {
namespace plugin_registry_test {
namespace fs = std::filesystem;
using test::fixture_dir;
using test::fixture_lib;
using Events = std::vector<std::string>;

std::string host_abi() {
  return std::to_string(NIMBUS_ABI_MAJOR) + "." + std::to_string(NIMBUS_ABI_MINOR) + "." +
         std::to_string(NIMBUS_ABI_PATCH);
}

class PluginDiscovery : public ::testing::Test {
 protected:
  // Discovers `cases` with a fresh registry and returns the single record they produce.
  const PluginRecord &only_record(std::initializer_list<std::string> cases) {
    discover(cases);
    EXPECT_EQ(registry_->records().size(), 1u);
    static const PluginRecord none;
    return registry_->records().empty() ? none : registry_->records().front();
  }
  void discover(std::initializer_list<std::string> cases) {
    std::vector<std::string> dirs;
    for (const auto &c : cases) dirs.push_back(fixture_dir(c));
    registry_->discover(dirs, host_.get());
  }
  // Asserts the single record is a refusal logged exactly as `line` (one warning line, nothing else).
  void expect_refused(const PluginRecord &rec, const std::string &path, const std::string &reason) {
    EXPECT_EQ(rec.path, path);
    EXPECT_FALSE(rec.loaded);
    EXPECT_EQ(rec.status, reason);
    EXPECT_EQ(log_.warnings(), Events{"refused " + path + ": " + reason});
  }

  test::Markers markers_;  // first: fixtures read its directory while the registry is alive
  test::LogCapture log_;
  test::FakeHost host_;
  std::unique_ptr<PluginRegistry> registry_ = std::make_unique<PluginRegistry>(log_.sink());
};

TEST_F(PluginDiscovery, LoadsTheGoodFixture) {
  const auto &rec = only_record({"good"});
  EXPECT_EQ(rec.path, fixture_lib("good", "good"));
  EXPECT_TRUE(rec.loaded);
  EXPECT_EQ(rec.status, "loaded");
  EXPECT_TRUE(rec.has_abi);
  EXPECT_EQ(rec.abi.major, NIMBUS_ABI_MAJOR);
  EXPECT_EQ(rec.abi.minor, NIMBUS_ABI_MINOR);
  EXPECT_TRUE(rec.has_descriptor);
  EXPECT_EQ(rec.id, "org.nimbus.test.good");
  EXPECT_EQ(rec.name, "Fixture good");
  EXPECT_EQ(rec.vendor, "Nimbus tests");
  EXPECT_EQ(rec.kind, NIMBUS_KIND_INTEGRATOR);
  EXPECT_EQ(rec.version.major, 1);
  EXPECT_EQ(rec.version.minor, 2);
  EXPECT_EQ(rec.version.patch, 3);
  EXPECT_EQ(rec.features, Events{"progressive"});
  EXPECT_EQ(rec.required_services, Events{"nimbus.host.film@1"});
  EXPECT_TRUE(log_.warnings().empty());
  EXPECT_EQ(log_.at(NIMBUS_LOG_INFO),
            Events{"loaded " + rec.path + ": integrator 'org.nimbus.test.good' 1.2.3 (SDK ABI " + host_abi() +
                   ")"});
  // init once with the absolute path; deinit only when the registry goes.
  EXPECT_EQ(markers_.events("good").front(), "init " + rec.path);
  EXPECT_EQ(markers_.lifecycle("good"), Events{"init"});
  registry_.reset();
  EXPECT_EQ(markers_.lifecycle("good"), (Events{"init", "deinit"}));
  EXPECT_EQ(markers_.events("good").back(), "deinit 0");  // the library's refcount is back to zero
}

// The ABI refusals: exact line with both versions, and not one call beyond the entry function.
TEST_F(PluginDiscovery, RefusesNewerMinorWithoutCallingIt) {
  const auto &rec = only_record({"abi_newer_minor"});
  const std::string plugin_abi =
      std::to_string(NIMBUS_ABI_MAJOR) + "." + std::to_string(NIMBUS_ABI_MINOR + 1) + "." + "0";
  expect_refused(rec, fixture_lib("abi_newer_minor", "abi_newer_minor"),
                 "built for SDK ABI " + plugin_abi + ", host provides " + host_abi() + " (newer minor)");
  EXPECT_TRUE(rec.has_abi);
  EXPECT_EQ(rec.abi.minor, NIMBUS_ABI_MINOR + 1);
  EXPECT_FALSE(rec.has_descriptor);
  EXPECT_FALSE(markers_.exists("abi_newer_minor"));
}

TEST_F(PluginDiscovery, RefusesNextMajorWithoutCallingIt) {
  const auto &rec = only_record({"abi_next_major"});
  expect_refused(rec, fixture_lib("abi_next_major", "abi_next_major"),
                 "built for SDK ABI " + std::to_string(NIMBUS_ABI_MAJOR + 1) + ".0.0, host provides " +
                     host_abi() + " (different major)");
  EXPECT_FALSE(markers_.exists("abi_next_major"));
}

TEST_F(PluginDiscovery, RefusesZeroDotXWithoutCallingIt) {
  const auto &rec = only_record({"abi_zero"});
  expect_refused(rec, fixture_lib("abi_zero", "abi_zero"),
                 "built for SDK ABI 0.9.0, host provides " + host_abi() + " (different major)");
  EXPECT_FALSE(markers_.exists("abi_zero"));
}

TEST_F(PluginDiscovery, RefusesEntrySmallerThanOneDotZero) {
  const auto &rec = only_record({"entry_small"});
  expect_refused(rec, fixture_lib("entry_small", "entry_small"),
                 "entry struct_size 16 is smaller than SDK ABI 1.0's 56 (built for SDK ABI " + host_abi() +
                     ", host provides " + host_abi() + ")");
  EXPECT_FALSE(markers_.exists("entry_small"));
}

TEST_F(PluginDiscovery, RefusesEntryTooSmallForAVersion) {
  const auto &rec = only_record({"entry_tiny"});
  expect_refused(rec, fixture_lib("entry_tiny", "entry_tiny"),
                 "entry struct_size 4 is too small to hold a version");
  EXPECT_FALSE(rec.has_abi);
  EXPECT_FALSE(markers_.exists("entry_tiny"));
}

TEST_F(PluginDiscovery, RefusesEntryReturningNull) {
  const auto &rec = only_record({"entry_null"});
  expect_refused(rec, fixture_lib("entry_null", "entry_null"), "nimbus_plugin_entry() returned NULL");
  EXPECT_FALSE(markers_.exists("entry_null"));
}

TEST_F(PluginDiscovery, RefusesLibraryWithoutEntrySymbol) {
  const auto &rec = only_record({"no_entry"});
  expect_refused(rec, fixture_lib("no_entry", "no_entry"),
                 "no entry symbol 'nimbus_plugin_entry' (not a Nimbus plugin)");
  EXPECT_FALSE(markers_.exists("no_entry"));
}

TEST_F(PluginDiscovery, RefusesLibraryWithUnresolvedSymbolAtLoad) {
  // RTLD_NOW: the missing symbol fails dlopen, with dlerror's text, instead of crashing at first use.
  const auto &rec = only_record({"unresolved"});
  const std::string path = fixture_lib("unresolved", "unresolved");
  EXPECT_FALSE(rec.loaded);
  EXPECT_EQ(rec.status.rfind("not a loadable shared library (", 0), 0u) << rec.status;
  EXPECT_NE(rec.status.find("undefined symbol: nimbus_fixture_symbol_nobody_defines"), std::string::npos)
      << rec.status;
  EXPECT_EQ(log_.warnings(), Events{"refused " + path + ": " + rec.status});
  EXPECT_FALSE(markers_.exists("unresolved"));
}

TEST_F(PluginDiscovery, RefusesATextFileNamedSo) {
  test::ScratchDir dir;
  const std::string junk = dir.str() + "/libjunk.so";
  std::ofstream(junk) << "not an ELF file\n";
  registry_->discover({dir.str()}, host_.get());
  ASSERT_EQ(registry_->records().size(), 1u);
  const auto &rec = registry_->records()[0];
  // dlerror names the file and the reason; the exact wording belongs to glibc.
  EXPECT_EQ(rec.status.rfind("not a loadable shared library (" + junk + ": ", 0), 0u) << rec.status;
  EXPECT_EQ(log_.warnings(), Events{"refused " + junk + ": " + rec.status});
}

TEST_F(PluginDiscovery, RefusesWhenInitFailsAndDoesNotDeinit) {
  const auto &rec = only_record({"init_fails"});
  expect_refused(rec, fixture_lib("init_fails", "init_fails"), "init failed: internal error (status -6)");
  EXPECT_EQ(markers_.lifecycle("init_fails"), Events{"init"});
  registry_.reset();
  EXPECT_EQ(markers_.lifecycle("init_fails"), Events{"init"});
}

TEST_F(PluginDiscovery, RefusesEmptyLibraryAndDeinitsIt) {
  const auto &rec = only_record({"count_zero"});
  expect_refused(rec, fixture_lib("count_zero", "count_zero"),
                 "library provides no plugins (count() returned 0)");
  EXPECT_EQ(markers_.lifecycle("count_zero"), (Events{"init", "deinit"}));
}

TEST_F(PluginDiscovery, RefusesNullDescriptor) {
  const auto &rec = only_record({"descriptor_null"});
  expect_refused(rec, fixture_lib("descriptor_null", "descriptor_null"), "descriptor 0 is NULL");
  EXPECT_EQ(markers_.lifecycle("descriptor_null"), (Events{"init", "deinit"}));
}

TEST_F(PluginDiscovery, RefusesIdWithSpace) {
  const auto &rec = only_record({"bad_id_space"});
  expect_refused(rec, fixture_lib("bad_id_space", "bad_id_space"),
                 "descriptor 0 has a malformed id 'bad id' (expected non-empty ASCII without spaces)");
  EXPECT_FALSE(rec.has_descriptor);
  EXPECT_EQ(markers_.lifecycle("bad_id_space"), (Events{"init", "deinit"}));
}

TEST_F(PluginDiscovery, RefusesEmptyId) {
  const auto &rec = only_record({"bad_id_empty"});
  expect_refused(rec, fixture_lib("bad_id_empty", "bad_id_empty"),
                 "descriptor 0 has a malformed id '' (expected non-empty ASCII without spaces)");
}

TEST_F(PluginDiscovery, RefusesUnknownKind) {
  const auto &rec = only_record({"bad_kind"});
  expect_refused(rec, fixture_lib("bad_kind", "bad_kind"),
                 "plugin 'org.nimbus.test.good' has unknown kind 99");
}

TEST_F(PluginDiscovery, RefusesMissingRequiredServiceNamingIt) {
  const auto &rec = only_record({"missing_service"});
  expect_refused(
      rec, fixture_lib("missing_service", "missing_service"),
      "plugin 'org.nimbus.test.needy' requires host service 'org.example.missing@1', which this host "
      "does not provide");
  EXPECT_TRUE(rec.has_descriptor);  // the listing still shows what the plugin is
  EXPECT_EQ(rec.id, "org.nimbus.test.needy");
  EXPECT_EQ(markers_.lifecycle("missing_service"), (Events{"init", "deinit"}));
}

TEST_F(PluginDiscovery, WithoutAHostNoRequiredServiceIsProvided) {
  registry_->discover({fixture_dir("good")}, nullptr);
  ASSERT_EQ(registry_->records().size(), 1u);
  EXPECT_FALSE(registry_->records()[0].loaded);
  EXPECT_EQ(registry_->records()[0].status,
            "plugin 'org.nimbus.test.good' requires host service 'nimbus.host.film@1', which this host does "
            "not provide");
}

TEST_F(PluginDiscovery, FirstOfDuplicateIdsWinsInFilenameOrder) {
  discover({"duplicate"});
  const auto &recs = registry_->records();
  ASSERT_EQ(recs.size(), 2u);
  const std::string a = fixture_lib("duplicate", "dup_a"), b = fixture_lib("duplicate", "dup_b");
  EXPECT_EQ(recs[0].path, a);
  EXPECT_TRUE(recs[0].loaded);
  EXPECT_EQ(recs[1].path, b);
  EXPECT_FALSE(recs[1].loaded);
  EXPECT_EQ(log_.warnings(),
            Events{"refused " + b + ": duplicate plugin id 'org.nimbus.test.dup', already provided by " + a});
  EXPECT_EQ(registry_->find("org.nimbus.test.dup")->path, a);
  EXPECT_EQ(markers_.lifecycle("dup_b"), (Events{"init", "deinit"}));  // refused after init: deinit at once
  EXPECT_EQ(markers_.lifecycle("dup_a"), Events{"init"});
}

TEST_F(PluginDiscovery, EarlierDirectoryWinsOverLaterOnes) {
  discover({"duplicate_other", "duplicate"});
  const std::string c = fixture_lib("duplicate_other", "dup_c");
  const std::string suffix = ": duplicate plugin id 'org.nimbus.test.dup', already provided by " + c;
  EXPECT_EQ(log_.warnings(), (Events{"refused " + fixture_lib("duplicate", "dup_a") + suffix,
                                     "refused " + fixture_lib("duplicate", "dup_b") + suffix}));
  EXPECT_EQ(registry_->find("org.nimbus.test.dup")->path, c);
}

TEST_F(PluginDiscovery, ListsEveryPluginOfALibrary) {
  discover({"two_plugins"});
  const auto &recs = registry_->records();
  ASSERT_EQ(recs.size(), 2u);
  const std::string path = fixture_lib("two_plugins", "pair");
  EXPECT_EQ(recs[0].path, path);
  EXPECT_EQ(recs[0].id, "nimbus.pairpt");
  EXPECT_EQ(recs[0].kind, NIMBUS_KIND_INTEGRATOR);
  EXPECT_TRUE(recs[0].loaded);
  EXPECT_EQ(recs[1].path, path);
  EXPECT_EQ(recs[1].id, "nimbus.pairls");
  EXPECT_EQ(recs[1].kind, NIMBUS_KIND_LIGHT_SAMPLER);
  EXPECT_TRUE(recs[1].loaded);
  EXPECT_TRUE(log_.warnings().empty());
  EXPECT_EQ(markers_.lifecycle("pair"), Events{"init"});  // one init per library, not per plugin
  registry_.reset();
  EXPECT_EQ(markers_.lifecycle("pair"), (Events{"init", "deinit"}));
}

TEST_F(PluginDiscovery, RefusalsDoNotStopOtherPlugins) {
  test::ScratchDir junk_dir;
  std::ofstream(junk_dir.str() + "/libjunk.so") << "junk";
  std::vector<std::string> dirs{junk_dir.str()};
  const std::vector<std::string> cases{"abi_newer_minor", "abi_next_major", "abi_zero",        "entry_small",
                                       "entry_tiny",      "entry_null",     "no_entry",        "unresolved",
                                       "init_fails",      "count_zero",     "descriptor_null", "bad_id_space",
                                       "bad_id_empty",    "bad_kind",       "missing_service", "good",
                                       "duplicate",       "two_plugins"};
  for (const auto &c : cases) dirs.push_back(fixture_dir(c));
  registry_->discover(dirs, host_.get());

  size_t loaded = 0;
  for (const auto &r : registry_->records()) loaded += r.loaded;
  EXPECT_EQ(loaded, 4u);  // good, dup_a, pairpt, pairls
  EXPECT_NE(registry_->find("org.nimbus.test.good"), nullptr);
  EXPECT_NE(registry_->find("nimbus.pairls"), nullptr);
  EXPECT_EQ(registry_->records().size(), 21u);  // every file, one record per plugin of the pair
  // One warning line per refusal, each naming its own file.
  const auto warnings = log_.warnings();
  ASSERT_EQ(warnings.size(), registry_->records().size() - loaded);
  size_t w = 0;
  for (const auto &r : registry_->records()) {
    if (!r.loaded) {
      EXPECT_EQ(warnings[w++], "refused " + r.path + ": " + r.status);
    }
  }
}

TEST_F(PluginDiscovery, OpensOnlySoFilesDirectlyInside) {
  test::ScratchDir dir;
  fs::create_directories(dir.path() / "nested.so");  // a directory, not a file
  fs::create_directories(dir.path() / "sub");
  fs::copy_file(fixture_lib("good", "good"), dir.path() / "sub" / "libgood.so");  // one level down
  fs::copy_file(fixture_lib("good", "good"), dir.path() / "libgood.so.1");        // not *.so
  fs::copy_file(fixture_lib("good", "good"), dir.path() / "libgood.txt");
  registry_->discover({dir.str()}, host_.get());
  EXPECT_TRUE(registry_->records().empty());
  EXPECT_TRUE(log_.lines.empty());
}

TEST_F(PluginDiscovery, FollowsSymlinkedLibrariesAndSkipsFilesSeenTwice) {
  test::ScratchDir dir;
  const std::string link = dir.str() + "/libgood-link.so";
  fs::create_symlink(fixture_lib("good", "good"), link);
  registry_->discover({dir.str(), fixture_dir("good")}, host_.get());
  registry_->discover({fixture_dir("good")}, host_.get());
  ASSERT_EQ(registry_->records().size(), 1u);
  EXPECT_EQ(registry_->records()[0].path, link);
  EXPECT_TRUE(registry_->records()[0].loaded);
  EXPECT_EQ(markers_.lifecycle("good"), Events{"init"});
}

TEST_F(PluginDiscovery, WarnsAboutAMissingDirectory) {
  test::ScratchDir dir;
  const std::string missing = dir.str() + "/nope";
  registry_->discover({missing + "/", fixture_dir("good")}, host_.get());
  EXPECT_EQ(log_.warnings(), Events{"plugin directory " + missing + " does not exist or is not a directory"});
  EXPECT_EQ(registry_->records().size(), 1u);
}

TEST_F(PluginDiscovery, RelativeDirectoriesAreLoggedAbsolute) {
  const fs::path old = fs::current_path();
  fs::current_path(NIMBUS_FIXTURE_ROOT);
  registry_->discover({"./entry_null"}, host_.get());
  fs::current_path(old);
  EXPECT_EQ(log_.warnings(), Events{"refused " + fixture_lib("entry_null", "entry_null") +
                                    ": nimbus_plugin_entry() returned NULL"});
}

TEST(PluginRegistryLog, DefaultSinkWritesWarningsToStderr) {
  testing::internal::CaptureStderr();
  {
    PluginRegistry registry;
    registry.discover({fixture_dir("entry_null"), fixture_dir("two_plugins")}, nullptr);
  }
  const std::string err = testing::internal::GetCapturedStderr();
  const std::string null_line = "nimbus: warning: refused " + fixture_lib("entry_null", "entry_null") +
                                ": nimbus_plugin_entry() returned NULL\n";
  // The pair needs nimbus.host.rng@1, which a NULL host lacks; info lines ("loaded ...") are not printed.
  const std::string pair = fixture_lib("two_plugins", "pair");
  EXPECT_EQ(err,
            null_line + "nimbus: warning: refused " + pair +
                ": plugin 'nimbus.pairpt' requires host service 'nimbus.host.rng@1', which this host does "
                "not provide\n");
}

}  // namespace plugin_registry_test
}  // namespace nimbus
