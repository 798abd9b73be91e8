// A 1.x host accepts every table at least as large as SDK 1.0 made it (sdk-idioms.md §1.3): the frozen 1.0
// integrator passes the host's check under the current (newer) headers, a table shorter than 1.0 is
// refused with a message naming the plugin and both sizes.
#include <gtest/gtest.h>

#include "abi/host_services.hpp"
#include "abi_test_support.hpp"
#include "loader/plugin_interface.hpp"
#include "loader/plugin_registry.hpp"
#include "loader/plugin_version.hpp"

namespace nimbus::abi_test {
namespace table_size_test {

TEST(TableSizes, HostIsNewerThanTheFrozenFixtures) {
  // Otherwise the frozen-1.0 tests would only prove that 1.0 loads into 1.0.
  EXPECT_EQ(kHostAbi.major, 1);
  EXPECT_GE(kHostAbi.minor, 1);
}

TEST(TableSizes, MinimumsAreThe10Sizes) {
  // Literal SDK 1.0 sizes (tests/abi/layout_1_0.c), not sizeof() of the live structs, which may grow.
  EXPECT_EQ(kIntegratorSize10, 56u);
  EXPECT_EQ(kLightSamplerMinSize, 40u);
  EXPECT_LE(kIntegratorSize10, sizeof(nimbus_integrator_v1_t));
}

class FrozenIntegratorTable : public ::testing::Test {
 protected:
  void SetUp() override { registry_.discover({fixture_dir()}, host_.host()); }
  HostServices host_{nullptr};
  PluginRegistry registry_{[](int, const std::string &) {}};
};

TEST_F(FrozenIntegratorTable, Abi10IntegratorPassesTheHostCheck) {
  auto created = registry_.create("org.nimbus.abi.direct", NIMBUS_KIND_INTEGRATOR, host_.host());
  ASSERT_TRUE(created) << created.error().message;
  const nimbus_plugin_t *p = created.value();
  auto t = interface_of<nimbus_integrator_v1_t>(p, "org.nimbus.abi.direct", NIMBUS_IFACE_INTEGRATOR,
                                                kIntegratorSize10);
  ASSERT_TRUE(t) << t.error().message;
  EXPECT_EQ(t.value()->struct_size, kIntegratorSize10) << "the fixture's table is the 1.0 size";
  registry_.destroy(p);
}

// A hand-made plugin whose integrator table ends one hook before 1.0's (no end_render).
const nimbus_descriptor_t kShortDesc = {{sizeof(nimbus_descriptor_t), NIMBUS_S_TYPE_DESCRIPTOR, nullptr},
                                        "org.nimbus.test.short",
                                        "short table",
                                        "tests",
                                        {1, 0, 0, 0},
                                        NIMBUS_KIND_INTEGRATOR,
                                        0,
                                        nullptr,
                                        nullptr};
nimbus_integrator_v1_t short_table() {
  nimbus_integrator_v1_t t{};
  t.struct_size = uint32_t(offsetof(nimbus_integrator_v1_t, end_render));
  return t;
}
const nimbus_integrator_v1_t kShortTable = short_table();
const nimbus_plugin_t kShortPlugin = {
    sizeof(nimbus_plugin_t),
    0,
    &kShortDesc,
    nullptr,
    nullptr,
    nullptr,
    [](const nimbus_plugin_t *, const char *id, uint32_t rev) -> const void * {
      return rev == 1 && std::string_view(id) == NIMBUS_IFACE_INTEGRATOR ? &kShortTable : nullptr;
    }};

TEST(TableSizes, ShorterThan10IsRefusedWithBothSizes) {
  auto t = interface_of<nimbus_integrator_v1_t>(&kShortPlugin, kShortDesc.id, NIMBUS_IFACE_INTEGRATOR,
                                                kIntegratorSize10);
  ASSERT_FALSE(t);
  EXPECT_EQ(t.error().message,
            "plugin 'org.nimbus.test.short': nimbus.iface.integrator@1 table is too small (48 bytes; SDK 1.0 "
            "tables have at least 56)");
}

TEST(TableSizes, MissingInterfaceIsNamed) {
  auto t = interface_of<nimbus_light_sampler_v1_t>(&kShortPlugin, kShortDesc.id, NIMBUS_IFACE_LIGHT_SAMPLER,
                                                   kLightSamplerMinSize);
  ASSERT_FALSE(t);
  EXPECT_EQ(t.error().message,
            "plugin 'org.nimbus.test.short' does not provide nimbus.iface.light-sampler@1");
}

}  // namespace table_size_test
}  // namespace nimbus::abi_test
