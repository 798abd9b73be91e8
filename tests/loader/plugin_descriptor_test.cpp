// Descriptor validation and "id@rev" parsing, on descriptors built in memory.
#include <gtest/gtest.h>

#include "loader/plugin_descriptor.hpp"
#include "plugin_test_support.hpp"

namespace nimbus {
namespace plugin_descriptor_test {

const char *const kFeatures[] = {"progressive", "lightmix", nullptr};
const char *const kRequires[] = {"nimbus.host.film@1", nullptr};

nimbus_descriptor_t valid() {
  nimbus_descriptor_t d{};
  d.header = {sizeof(nimbus_descriptor_t), NIMBUS_S_TYPE_DESCRIPTOR, nullptr};
  d.id = "org.example.pt";
  d.name = "Example";
  d.vendor = "Example Inc.";
  d.version = {2, 1, 0, 0};
  d.kind = NIMBUS_KIND_INTEGRATOR;
  d.features = kFeatures;
  d.required_services = kRequires;
  return d;
}

std::string error_of(const nimbus_descriptor_t &d) {
  auto r = read_descriptor(&d, 3);
  EXPECT_FALSE(r.copy.has_value());
  return r.error;
}

TEST(PluginDescriptor, CopiesAValidDescriptor) {
  const auto d = valid();
  auto r = read_descriptor(&d, 0);
  ASSERT_TRUE(r.copy) << r.error;
  EXPECT_EQ(r.copy->id, "org.example.pt");
  EXPECT_EQ(r.copy->name, "Example");
  EXPECT_EQ(r.copy->vendor, "Example Inc.");
  EXPECT_EQ(r.copy->kind, NIMBUS_KIND_INTEGRATOR);
  EXPECT_EQ(r.copy->version.major, 2);
  EXPECT_EQ(r.copy->version.minor, 1);
  EXPECT_EQ(r.copy->features, (std::vector<std::string>{"progressive", "lightmix"}));
  EXPECT_EQ(r.copy->required_services, (std::vector<std::string>{"nimbus.host.film@1"}));
}

TEST(PluginDescriptor, NullListsAreEmpty) {
  auto d = valid();
  d.features = nullptr;
  d.required_services = nullptr;
  auto r = read_descriptor(&d, 0);
  ASSERT_TRUE(r.copy) << r.error;
  EXPECT_TRUE(r.copy->features.empty());
  EXPECT_TRUE(r.copy->required_services.empty());
}

TEST(PluginDescriptor, RefusesMalformed) {
  EXPECT_EQ(read_descriptor(nullptr, 3).error, "descriptor 3 is NULL");
  auto d = valid();
  d.header.struct_size = 16;
  EXPECT_EQ(error_of(d), "descriptor 3 has struct_size 16, smaller than SDK ABI 1.0's 72");
  d = valid();
  d.header.s_type = 7;
  EXPECT_EQ(error_of(d), "descriptor 3 has s_type 7, expected 1");
  d = valid();
  d.id = nullptr;
  EXPECT_EQ(error_of(d), "descriptor 3 has no id");
  d.id = "";
  EXPECT_EQ(error_of(d), "descriptor 3 has a malformed id '' (expected non-empty ASCII without spaces)");
  d.id = "org.example pt";
  EXPECT_EQ(error_of(d),
            "descriptor 3 has a malformed id 'org.example pt' (expected non-empty ASCII without spaces)");
  d.id = "tab\there";
  EXPECT_FALSE(read_descriptor(&d, 3).copy);
  d.id = "caf\xc3\xa9";  // non-ASCII
  EXPECT_FALSE(read_descriptor(&d, 3).copy);
  d = valid();
  d.name = nullptr;
  EXPECT_EQ(error_of(d), "plugin 'org.example.pt' has no name");
  d = valid();
  d.vendor = nullptr;
  EXPECT_EQ(error_of(d), "plugin 'org.example.pt' has no vendor");
  d = valid();
  d.kind = 99;
  EXPECT_EQ(error_of(d), "plugin 'org.example.pt' has unknown kind 99");
  d = valid();
  const char *const bad_service[] = {"nimbus.host.film", nullptr};
  d.required_services = bad_service;
  EXPECT_EQ(
      error_of(d),
      "plugin 'org.example.pt' has a malformed required service 'nimbus.host.film' (expected id@revision)");
}

TEST(PluginDescriptor, RefusesAnUnterminatedList) {
  std::vector<const char *> endless(300, "progressive");  // no NULL within the bound
  endless.push_back(nullptr);
  auto d = valid();
  d.features = endless.data();
  EXPECT_EQ(error_of(d), "plugin 'org.example.pt' lists more than 256 features (missing NULL terminator?)");
}

TEST(PluginDescriptor, ParsesServiceRefs) {
  auto r = parse_service_ref("nimbus.host.film@1");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->id, "nimbus.host.film");
  EXPECT_EQ(r->revision, 1u);
  r = parse_service_ref("org.example.a@b@12");  // the revision follows the last '@'
  ASSERT_TRUE(r);
  EXPECT_EQ(r->id, "org.example.a@b");
  EXPECT_EQ(r->revision, 12u);
  for (const char *bad :
       {"", "nimbus.host.film", "@1", "nimbus.host.film@", "x@1a", "x@-1", "x@ 1", "x@99999999999"}) {
    EXPECT_FALSE(parse_service_ref(bad)) << bad;
  }
}

TEST(PluginDescriptor, RequiredServicesAskTheHost) {
  DescriptorCopy d;
  d.id = "org.example.pt";
  d.required_services = {"nimbus.host.film@1", "nimbus.host.rng@1"};
  test::FakeHost host;
  EXPECT_FALSE(check_required_services(d, host.get()));
  d.required_services.push_back("nimbus.host.film@2");  // a revision the host lacks counts as missing
  EXPECT_EQ(check_required_services(d, host.get()).value(),
            "plugin 'org.example.pt' requires host service 'nimbus.host.film@2', which this host does not "
            "provide");
  d.required_services = {"nimbus.host.film@1"};
  EXPECT_TRUE(check_required_services(d, nullptr));  // no host, no services
  d.required_services.clear();
  EXPECT_FALSE(check_required_services(d, nullptr));
}

TEST(PluginDescriptor, KindNames) {
  EXPECT_EQ(kind_name(NIMBUS_KIND_INTEGRATOR), "integrator");
  EXPECT_EQ(kind_name(NIMBUS_KIND_LIGHT_SAMPLER), "light-sampler");
  EXPECT_EQ(kind_name(NIMBUS_KIND_GUIDING), "guiding");
  EXPECT_EQ(kind_name(42), "unknown kind 42");
  EXPECT_EQ(kind_plural(NIMBUS_KIND_LIGHT_SAMPLER), "light-samplers");
  EXPECT_EQ(kind_plural(NIMBUS_KIND_GUIDING), "guiding plugins");
  EXPECT_EQ(kind_with_article(NIMBUS_KIND_INTEGRATOR), "an integrator");
  EXPECT_EQ(kind_with_article(NIMBUS_KIND_LIGHT_SAMPLER), "a light-sampler");
}

}  // namespace plugin_descriptor_test
}  // namespace nimbus
