// The mutation size's schedule (mutation_schedule.hpp): the adaptation rule, passes that go forward, the
// replay of the last pass, and its state's format checks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "mutation_schedule.hpp"

namespace nimbus::guide_test {
namespace schedule_test {

using guide::MutationSchedule;

TEST(MutationSchedule, AdaptsTowardsAnAcceptanceOf0234WithinItsClamps) {
  EXPECT_DOUBLE_EQ(MutationSchedule::adapted(0.05, 234, 1000), 0.05);
  EXPECT_DOUBLE_EQ(MutationSchedule::adapted(0.05, 1000, 1000), 0.05 * std::exp(0.766));
  EXPECT_DOUBLE_EQ(MutationSchedule::adapted(0.05, 0, 1000), 0.05 * std::exp(-0.234));
  EXPECT_DOUBLE_EQ(MutationSchedule::adapted(0.45, 900, 1000), 0.5);
  EXPECT_DOUBLE_EQ(MutationSchedule::adapted(1.1e-4, 0, 1000), 1e-4);
  EXPECT_DOUBLE_EQ(MutationSchedule::adapted(0.2, 0, 0), 0.2) << "no proposals, no information";
}

TEST(MutationSchedule, PassesGoForwardAndTheLastOneReplays) {
  MutationSchedule s;
  EXPECT_FALSE(s.end(1, 1)) << "no pass begun";
  EXPECT_FALSE(s.begin(0)) << "passes are 1-based";
  EXPECT_EQ(s.begin(1), MutationSchedule::kInitial);
  EXPECT_TRUE(s.end(1000, 1000));
  const double d2 = 0.05 * std::exp(0.766);
  EXPECT_DOUBLE_EQ(*s.begin(3), d2) << "a pass may be skipped (an unguided pass)";
  EXPECT_TRUE(s.end(0, 1000));
  const double d4 = d2 * std::exp(-0.234);
  // Pass 3 again (a resumed render rebuilding it): its own d, and its end changes nothing.
  EXPECT_DOUBLE_EQ(*s.begin(3), d2);
  EXPECT_TRUE(s.end(1000, 1000));
  EXPECT_DOUBLE_EQ(s.next_d(), d4);
  EXPECT_FALSE(s.begin(2)) << "before the last pass";
  EXPECT_DOUBLE_EQ(*s.begin(4), d4);
  s.reset();
  EXPECT_EQ(s.begin(1), MutationSchedule::kInitial) << "prepare starts a new render";
}

// The state as the render-state table moves it: bytes written by save, read back by restore.
std::vector<uint8_t> saved(const MutationSchedule &s) {
  std::vector<uint8_t> bytes;
  const nimbus_state_writer_t w{
      sizeof w, 0, &bytes, [](const nimbus_state_writer_t *w, const void *p, uint64_t n) {
        auto &out = *static_cast<std::vector<uint8_t> *>(w->host_data);
        out.insert(out.end(), static_cast<const uint8_t *>(p), static_cast<const uint8_t *>(p) + n);
        return NIMBUS_OK;
      }};
  sdk::StateWriter out(&w);
  s.save(out);
  EXPECT_EQ(out.status(), NIMBUS_OK);
  return bytes;
}
nimbus_status_t restored(MutationSchedule &s, const std::vector<uint8_t> &bytes) {
  sdk::StateReader in(bytes.data(), bytes.size());
  return s.restore(in);
}

TEST(MutationSchedule, StateRoundTripKeepsTheReplay) {
  MutationSchedule s;
  s.begin(1), s.end(900, 1000);
  s.begin(2), s.end(100, 1000);
  MutationSchedule r;
  ASSERT_EQ(restored(r, saved(s)), NIMBUS_OK);
  EXPECT_EQ(r.begin(2), s.begin(2)) << "the replay's d";
  EXPECT_EQ(r.begin(3), s.begin(3));
}

TEST(MutationSchedule, RefusesStatesItCannotHold) {
  MutationSchedule s;
  s.begin(1), s.end(900, 1000);
  const std::vector<uint8_t> good = saved(s);
  const auto with_d = [&](size_t offset, double d) {
    std::vector<uint8_t> b = good;
    std::memcpy(b.data() + offset, &d, sizeof d);
    return b;
  };
  std::vector<uint8_t> version = good;
  version[0] += 1;
  MutationSchedule r;
  EXPECT_EQ(restored(r, version), NIMBUS_E_VERSION);
  EXPECT_EQ(restored(r, {good.begin(), good.end() - 1}), NIMBUS_E_INVALID_ARG);
  EXPECT_EQ(restored(r, with_d(12, 0.51)), NIMBUS_E_INVALID_ARG);
  EXPECT_EQ(restored(r, with_d(20, 5e-5)), NIMBUS_E_INVALID_ARG);
  EXPECT_EQ(restored(r, with_d(20, INFINITY)), NIMBUS_E_INVALID_ARG);
  EXPECT_EQ(r.begin(1), MutationSchedule::kInitial) << "unchanged by the refusals";
}

}  // namespace schedule_test
}  // namespace nimbus::guide_test
