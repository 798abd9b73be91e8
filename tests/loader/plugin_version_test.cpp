// The ABI compatibility rule, checked over every combination of small versions against an independent
// statement of the rule, plus the exact wording of each refusal.
#include <gtest/gtest.h>

#include "loader/plugin_version.hpp"

namespace nimbus {
namespace plugin_version_test {

nimbus_version_t v(uint16_t major, uint16_t minor, uint16_t patch) { return {major, minor, patch, 0}; }

TEST(PluginVersion, FormatsMajorMinorPatch) {
  EXPECT_EQ(format_version(v(1, 4, 0)), "1.4.0");
  EXPECT_EQ(format_version(v(65535, 0, 12)), "65535.0.12");
  EXPECT_EQ(format_version({2, 3, 4, 99}), "2.3.4");  // reserved is not part of the version
}

TEST(PluginVersion, ExhaustiveOverSmallVersions) {
  int loads = 0, refusals = 0;
  for (uint16_t pm = 0; pm <= 3; ++pm)
    for (uint16_t pn = 0; pn <= 4; ++pn)
      for (uint16_t pp = 0; pp <= 2; ++pp)
        for (uint16_t hm = 0; hm <= 3; ++hm)
          for (uint16_t hn = 0; hn <= 4; ++hn)
            for (uint16_t hp = 0; hp <= 2; ++hp) {
              const bool same_major = pm == hm;
              const bool expect_load = same_major && (hm == 0 ? pn == hn : pn <= hn);
              const auto why = check_abi(v(pm, pn, pp), v(hm, hn, hp));
              SCOPED_TRACE(format_version(v(pm, pn, pp)) + " on host " + format_version(v(hm, hn, hp)));
              EXPECT_EQ(!why.has_value(), expect_load);
              if (!why) {
                ++loads;
                continue;
              }
              ++refusals;
              const std::string versions = "built for SDK ABI " + format_version(v(pm, pn, pp)) +
                                           ", host provides " + format_version(v(hm, hn, hp));
              const char *expected_why = !same_major ? " (different major)"
                                         : hm == 0   ? " (different minor in 0.x)"
                                                     : " (newer minor)";
              EXPECT_EQ(*why, versions + expected_why);
            }
  // Guard against a loop that silently tests nothing.
  EXPECT_GT(loads, 100);
  EXPECT_GT(refusals, 1000);
}

TEST(PluginVersion, PatchNeverMatters) {
  EXPECT_FALSE(check_abi(v(1, 0, 9), v(1, 0, 0)));
  EXPECT_FALSE(check_abi(v(1, 0, 0), v(1, 0, 9)));
  EXPECT_FALSE(check_abi(v(0, 3, 7), v(0, 3, 1)));
}

TEST(PluginVersion, ExactRefusalLines) {
  EXPECT_EQ(check_abi(v(2, 0, 0), v(1, 0, 0)).value(),
            "built for SDK ABI 2.0.0, host provides 1.0.0 (different major)");
  EXPECT_EQ(check_abi(v(1, 1, 0), v(1, 0, 0)).value(),
            "built for SDK ABI 1.1.0, host provides 1.0.0 (newer minor)");
  EXPECT_EQ(check_abi(v(1, 4, 0), v(1, 3, 2)).value(),
            "built for SDK ABI 1.4.0, host provides 1.3.2 (newer minor)");
  EXPECT_EQ(check_abi(v(0, 9, 0), v(1, 0, 0)).value(),
            "built for SDK ABI 0.9.0, host provides 1.0.0 (different major)");
  EXPECT_EQ(check_abi(v(0, 2, 0), v(0, 3, 0)).value(),
            "built for SDK ABI 0.2.0, host provides 0.3.0 (different minor in 0.x)");
}

TEST(PluginVersion, OlderMinorLoadsWithinMajor) {
  EXPECT_FALSE(check_abi(v(1, 0, 0), v(1, 3, 2)));
  EXPECT_FALSE(check_abi(v(1, 3, 0), v(1, 3, 2)));
}

TEST(PluginVersion, HostAbiIsTheHeadersVersion) {
  EXPECT_EQ(kHostAbi.major, NIMBUS_ABI_MAJOR);
  EXPECT_EQ(kHostAbi.minor, NIMBUS_ABI_MINOR);
  EXPECT_EQ(kHostAbi.patch, NIMBUS_ABI_PATCH);
}

}  // namespace plugin_version_test
}  // namespace nimbus
