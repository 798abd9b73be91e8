// Creating plugin instances by id: short names, kind checks, error texts, and the teardown order
// (instances destroyed before their library's deinit).
#include <gtest/gtest.h>

#include "plugin_test_support.hpp"

namespace nimbus {
namespace plugin_create_test {
using test::fixture_dir;
using Events = std::vector<std::string>;

class PluginCreate : public ::testing::Test {
 protected:
  void SetUp() override {
    registry_->discover({fixture_dir("good"), fixture_dir("two_plugins"), fixture_dir("plugin_init_fails")},
                        host_.get());
    ASSERT_TRUE(log_.warnings().empty());
  }
  test::Markers markers_;
  test::LogCapture log_;
  test::FakeHost host_;
  std::unique_ptr<PluginRegistry> registry_ = std::make_unique<PluginRegistry>(log_.sink());
};

TEST_F(PluginCreate, CreatesInitialisesAndDestroys) {
  auto created = registry_->create("org.nimbus.test.good", NIMBUS_KIND_INTEGRATOR, host_.get());
  ASSERT_TRUE(created) << created.error().message;
  const nimbus_plugin_t *plugin = created.value();
  ASSERT_NE(plugin, nullptr);
  EXPECT_STREQ(plugin->desc->id, "org.nimbus.test.good");
  EXPECT_EQ(plugin->plugin_data, host_.get());  // the fixture keeps the host it was created for
  EXPECT_EQ(markers_.lifecycle("good"), (Events{"init", "create", "plugin-init"}));
  registry_->destroy(plugin);
  EXPECT_EQ(markers_.lifecycle("good"), (Events{"init", "create", "plugin-init", "destroy"}));
  registry_.reset();
  EXPECT_EQ(markers_.lifecycle("good"), (Events{"init", "create", "plugin-init", "destroy", "deinit"}));
}

TEST_F(PluginCreate, ShortNameResolvesToFirstParty) {
  auto created = registry_->create("pairpt", NIMBUS_KIND_INTEGRATOR, host_.get());
  ASSERT_TRUE(created) << created.error().message;
  EXPECT_STREQ(created.value()->desc->id, "nimbus.pairpt");
  EXPECT_EQ(registry_->find("pairls")->id, "nimbus.pairls");
  EXPECT_EQ(registry_->find("org.nimbus.test.good")->id, "org.nimbus.test.good");
  EXPECT_EQ(registry_->find("good"), nullptr);  // only "nimbus." is implied
  registry_->destroy(created.value());
}

TEST_F(PluginCreate, UnknownIdListsTheAvailablePluginsOfThatKind) {
  auto created = registry_->create("nope", NIMBUS_KIND_INTEGRATOR, host_.get());
  ASSERT_FALSE(created);
  EXPECT_EQ(
      created.error().message,
      "no plugin with id 'nope' is loaded (available integrators: nimbus.pairpt, org.nimbus.test.badinit, "
      "org.nimbus.test.good)");
  created = registry_->create("nope", NIMBUS_KIND_LIGHT_SAMPLER, host_.get());
  EXPECT_EQ(created.error().message,
            "no plugin with id 'nope' is loaded (available light-samplers: nimbus.pairls)");
  created = registry_->create("nope", NIMBUS_KIND_GUIDING, host_.get());
  EXPECT_EQ(created.error().message, "no plugin with id 'nope' is loaded (no guiding plugins are loaded)");
  EXPECT_EQ(registry_->loaded_ids(NIMBUS_KIND_LIGHT_SAMPLER), Events{"nimbus.pairls"});
}

TEST_F(PluginCreate, WrongKindIsAnError) {
  auto created = registry_->create("pairls", NIMBUS_KIND_INTEGRATOR, host_.get());
  ASSERT_FALSE(created);
  EXPECT_EQ(created.error().message, "plugin 'nimbus.pairls' is a light-sampler, not an integrator");
  EXPECT_EQ(markers_.lifecycle("pair"), Events{"init"});  // create was never called
}

TEST_F(PluginCreate, InstanceInitFailureIsReportedAndTheInstanceDestroyed) {
  auto created = registry_->create("org.nimbus.test.badinit", NIMBUS_KIND_INTEGRATOR, host_.get());
  ASSERT_FALSE(created);
  EXPECT_EQ(created.error().message,
            "plugin 'org.nimbus.test.badinit' failed to initialise: internal error (status -6)");
  EXPECT_EQ(markers_.lifecycle("plugin_init_fails"), (Events{"init", "create", "plugin-init", "destroy"}));
}

TEST_F(PluginCreate, InstancesLeftAliveAreDestroyedBeforeDeinit) {
  auto a = registry_->create("pairpt", NIMBUS_KIND_INTEGRATOR, host_.get());
  auto b = registry_->create("pairls", NIMBUS_KIND_LIGHT_SAMPLER, host_.get());
  ASSERT_TRUE(a && b);
  registry_.reset();
  const auto events = markers_.events("pair");
  ASSERT_GE(events.size(), 3u);
  EXPECT_EQ(events[events.size() - 3], "destroy nimbus.pairls");  // newest first
  EXPECT_EQ(events[events.size() - 2], "destroy nimbus.pairpt");
  EXPECT_EQ(events.back(), "deinit 0");
}

TEST_F(PluginCreate, DestroyOfAForeignPointerIsRefusedAndLogged) {
  auto created = registry_->create("pairpt", NIMBUS_KIND_INTEGRATOR, host_.get());
  ASSERT_TRUE(created);
  registry_->destroy(created.value());
  registry_->destroy(created.value());  // double destroy must not reach the plugin again
  registry_->destroy(nullptr);
  EXPECT_EQ(log_.at(NIMBUS_LOG_ERROR),
            Events{"destroy of a plugin instance this registry did not create or already destroyed"});
  size_t destroys = 0;
  for (const auto &e : markers_.lifecycle("pair")) destroys += e == "destroy";
  EXPECT_EQ(destroys, 1u);
}

TEST_F(PluginCreate, NothingIsCreatedAfterDeinitAll) {
  registry_->deinit_all();
  registry_->deinit_all();  // idempotent
  auto created = registry_->create("org.nimbus.test.good", NIMBUS_KIND_INTEGRATOR, host_.get());
  ASSERT_FALSE(created);
  EXPECT_EQ(created.error().message,
            "no plugin with id 'org.nimbus.test.good' is loaded (no integrators are loaded)");
  size_t deinits = 0;
  for (const auto &e : markers_.lifecycle("good")) deinits += e == "deinit";
  EXPECT_EQ(deinits, 1u);
}

}  // namespace plugin_create_test
}  // namespace nimbus
