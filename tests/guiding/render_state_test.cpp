// nimbus.guide.metropolis's render state (nimbus.iface.render-state rev 1) through the ABI: a render
// resumed from a checkpoint, which first rebuilds its last pass (begin_pass with that pass's index again),
// traces exactly the paths of the uninterrupted render; bytes the guide cannot read are refused with a
// status and leave it as it was.
#include <gtest/gtest.h>

#include <cstring>

#include "loaded_guide.hpp"
#include "toy_targets.hpp"

namespace nimbus::guide_test {
namespace render_state_test {

constexpr uint32_t kDims = 4, kChains = 64;
constexpr uint64_t kBudget = kChains * 200;
const GaussianBump kBump{0.03};
const Target kBumpTarget = [](std::span<const float> u) { return kBump.at(u); };

PassRun run(const LoadedGuide &g, uint64_t pass) {
  PassRun r = g.run_pass(guide_pass(9, pass, kBudget, kChains, kDims), kBumpTarget);
  EXPECT_EQ(r.status, NIMBUS_OK) << "pass " << pass;
  return r;
}

void expect_same_paths(const PassRun &a, const PassRun &b, const char *what) {
  ASSERT_EQ(a.chains.size(), b.chains.size());
  for (size_t c = 0; c < a.chains.size(); ++c)
    EXPECT_TRUE(a.chains[c] == b.chains[c]) << what << ", chain " << c;
}

TEST(MetropolisGuideState, ResumedRenderTracesTheUninterruptedRendersPaths) {
  LoadedGuide uninterrupted;
  ASSERT_EQ(uninterrupted.prepare(), NIMBUS_OK);
  std::vector<PassRun> passes;
  for (uint64_t pass = 1; pass <= 4; ++pass) passes.push_back(run(uninterrupted, pass));
  // The mutation size moved between the passes (the start's acceptance is 0.55), so a resume that forgot
  // it, or replayed pass 2 with pass 3's size, would trace other paths.
  ASSERT_NE(passes[1].acceptance(), passes[2].acceptance());

  // Interrupted after pass 2: checkpointed, then resumed in a fresh instance (another process).
  std::vector<uint8_t> checkpoint;
  {
    LoadedGuide first;
    ASSERT_EQ(first.prepare(), NIMBUS_OK);
    run(first, 1), run(first, 2);
    checkpoint = first.save();
  }
  LoadedGuide resumed;
  ASSERT_EQ(resumed.prepare(), NIMBUS_OK);
  ASSERT_EQ(resumed.restore(checkpoint), NIMBUS_OK);
  // The rebuild of pass 2's photons replays pass 2, and its end_pass leaves the state alone.
  expect_same_paths(run(resumed, 2), passes[1], "replayed pass 2");
  EXPECT_EQ(resumed.save(), checkpoint);
  expect_same_paths(run(resumed, 3), passes[2], "pass 3");
  expect_same_paths(run(resumed, 4), passes[3], "pass 4");
  EXPECT_EQ(resumed.save(), uninterrupted.save());
}

TEST(MetropolisGuideState, UnreadableBytesAreRefusedAndChangeNothing) {
  LoadedGuide source;
  ASSERT_EQ(source.prepare(), NIMBUS_OK);
  const PassRun first = run(source, 1);
  const std::vector<uint8_t> good = source.save();
  // The format: a uint32 version, the last pass (uint64), its d and the next pass's d (doubles).
  ASSERT_EQ(good.size(), 4u + 8 + 8 + 8);

  LoadedGuide fresh;
  ASSERT_EQ(fresh.prepare(), NIMBUS_OK);
  const std::vector<uint8_t> untouched = fresh.save();
  const auto with_double = [&](size_t offset, double d) {
    std::vector<uint8_t> b = good;
    std::memcpy(b.data() + offset, &d, sizeof d);
    return b;
  };
  std::vector<uint8_t> other_version = good;
  other_version[0] ^= 0x40;
  std::vector<uint8_t> longer = good;
  longer.push_back(0);
  const std::vector<uint8_t> shorter(good.begin(), good.end() - 1);
  EXPECT_EQ(fresh.restore(other_version), NIMBUS_E_VERSION);
  EXPECT_EQ(fresh.restore({}), NIMBUS_E_INVALID_ARG);
  EXPECT_EQ(fresh.restore(shorter), NIMBUS_E_INVALID_ARG);
  EXPECT_EQ(fresh.restore(longer), NIMBUS_E_INVALID_ARG);
  EXPECT_EQ(fresh.restore(with_double(12, 0.7)), NIMBUS_E_INVALID_ARG) << "a d above 0.5";
  EXPECT_EQ(fresh.restore(with_double(20, 0.0)), NIMBUS_E_INVALID_ARG) << "a d below 1e-4";
  EXPECT_EQ(fresh.restore(with_double(20, std::nan(""))), NIMBUS_E_INVALID_ARG);
  EXPECT_EQ(fresh.save(), untouched);
  EXPECT_FALSE(fresh.messages().empty()) << "a refusal is logged";
  // Still a fresh guide: its first pass is the source's first pass.
  expect_same_paths(run(fresh, 1), first, "pass 1 after the refusals");
}

}  // namespace render_state_test
}  // namespace nimbus::guide_test
