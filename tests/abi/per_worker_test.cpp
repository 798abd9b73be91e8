// nimbus::sdk::PerWorker (nimbus.hpp): every worker's item on a cache line of its own, so that workers
// writing their items on every sample never share a line (false sharing), and iteration visits the items.
#include <gtest/gtest.h>
#include <nimbus/nimbus.hpp>

#include <cstdint>

namespace per_worker_test {

struct Record {  // the size of a camera path's sample record, not a multiple of a cache line
  float values[26];
};

template <class T>
void expect_one_line_each(uint32_t workers) {
  nimbus::sdk::PerWorker<T> w;
  w.resize(workers);
  ASSERT_EQ(w.size(), workers);
  for (uint32_t i = 0; i < workers; ++i) {
    const auto at = reinterpret_cast<uintptr_t>(&w[i]);
    EXPECT_EQ(at % 64, 0u) << "worker " << i;
    if (i > 0) {
      EXPECT_GE(at - reinterpret_cast<uintptr_t>(&w[i - 1]), 64u);
    }
  }
}

TEST(SdkPerWorker, EachItemStartsItsOwnCacheLine) {
  expect_one_line_each<uint8_t>(5);
  expect_one_line_each<uint64_t>(3);
  expect_one_line_each<Record>(4);
}

TEST(SdkPerWorker, IndexesAndIteratesTheSameItems) {
  nimbus::sdk::PerWorker<uint64_t> w;
  w.resize(4);
  for (uint64_t v : w) EXPECT_EQ(v, 0u);  // value-initialised
  const nimbus_thread_ctx_t ctx{sizeof(nimbus_thread_ctx_t), 2, 4, 0, nullptr, 0};
  w[ctx] = 7;
  w[3u] = 5;
  uint64_t sum = 0, n = 0;
  for (uint64_t &v : w) sum += v, ++n, v = 1;
  EXPECT_EQ(n, 4u);
  EXPECT_EQ(sum, 12u);
  EXPECT_EQ(w[0u] + w[1u] + w[2u] + w[3u], 4u);
  w.resize(2);  // begin_render of the next render: fresh items
  EXPECT_EQ(w[0u] + w[1u], 0u);
}

}  // namespace per_worker_test
