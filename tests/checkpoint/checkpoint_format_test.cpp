// The checkpoint round trip: sums, counts and header come back bit for bit, and continuing from a restored
// film gives exactly what continuing the original would.
#include <gtest/gtest.h>

#include <bit>
#include <filesystem>

#include "checkpoint_fixture.hpp"
#include "core/checksum.hpp"
#include "e2e_support.hpp"

namespace nimbus {
namespace checkpoint_format_test {

using e2e::TestDir;
using test::add_iteration;
using test::make_film;
using test::make_info;
using test::sum_bits;

const std::vector<std::string> kElements = {"beauty", "albedo", "depth", "lightmix.key"};

TEST(CheckpointFormat, RoundTripRestoresSumsCountsAndHeaderExactly) {
  TestDir dir;
  auto film = make_film();
  ASSERT_TRUE(film);
  for (uint64_t i = 1; i <= 3; ++i) add_iteration(*film, i);
  ASSERT_EQ(film->nonfinite_count(), 1u);
  const std::string path = dir.file("a.ckpt");
  const Status written = write_checkpoint(*film, path, make_info());
  ASSERT_TRUE(written.ok()) << written.error().message;

  auto restored = make_film();
  CheckpointInfo info = make_info();
  info.seconds = 0;
  const Status read = read_checkpoint(*restored, path, info);
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(info.iterations, 3u);
  EXPECT_EQ(info.seconds, make_info().seconds);
  EXPECT_EQ(restored->iterations(), 3u);
  EXPECT_EQ(restored->nonfinite_count(), 1u);
  for (const std::string &e : kElements) {
    EXPECT_FALSE(sum_bits(*film, e).empty()) << e;
    EXPECT_EQ(sum_bits(*restored, e), sum_bits(*film, e)) << e;
  }
  // Nothing but the checkpoint itself is left in the directory.
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"a.ckpt"});
}

TEST(CheckpointFormat, ContinuingARestoredFilmEqualsContinuingTheOriginal) {
  TestDir dir;
  auto original = make_film();
  for (uint64_t i = 1; i <= 2; ++i) add_iteration(*original, i);
  const std::string path = dir.file("b.ckpt");
  ASSERT_TRUE(write_checkpoint(*original, path, make_info()).ok());

  auto resumed = make_film();
  CheckpointInfo info = make_info();
  ASSERT_TRUE(read_checkpoint(*resumed, path, info).ok());
  for (uint64_t i = 3; i <= 5; ++i) {
    add_iteration(*original, i);
    add_iteration(*resumed, i);
  }
  for (const std::string &e : kElements) EXPECT_EQ(sum_bits(*resumed, e), sum_bits(*original, e)) << e;
  for (int32_t id : original->active_elements()) {
    const std::vector<float> a = original->resolve(id), b = resumed->resolve(id);
    ASSERT_EQ(a.size(), b.size());
    for (size_t k = 0; k < a.size(); ++k)
      ASSERT_EQ(std::bit_cast<uint32_t>(a[k]), std::bit_cast<uint32_t>(b[k])) << original->element_name(id);
  }
}

TEST(CheckpointFormat, PluginStatesComeBackByteForByte) {
  TestDir dir;
  auto film = make_film();
  add_iteration(*film, 1);
  CheckpointInfo written = make_info();
  written.states = {{"nimbus.caustics", {0, 1, 2, 255, 0}}, {"org.example.sampler", {}}};
  const std::string path = dir.file("s.ckpt");
  ASSERT_TRUE(write_checkpoint(*film, path, written).ok());
  auto restored = make_film();
  CheckpointInfo info = make_info();
  ASSERT_TRUE(read_checkpoint(*restored, path, info).ok());
  ASSERT_EQ(info.states.size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(info.states[k].plugin, written.states[k].plugin);
    EXPECT_EQ(info.states[k].bytes, written.states[k].bytes);
  }
}

TEST(CheckpointFormat, AVersionOneFileIsReadWithoutPluginStates) {
  // Version 1 ends its elements with the checksum: rewrite a version 2 file without states (count 0) as
  // version 1 and fix the checksum.
  TestDir dir;
  auto film = make_film();
  add_iteration(*film, 1);
  const std::string path = dir.file("v1.ckpt");
  ASSERT_TRUE(write_checkpoint(*film, path, make_info()).ok());
  std::string b = e2e::read_bytes(path);
  ASSERT_GT(b.size(), 20u);
  b[8] = 1;
  b.erase(b.size() - 12, 4);  // the u32 state count before the checksum
  Checksum sum;
  sum.update(reinterpret_cast<const uint8_t *>(b.data()), b.size() - 8);
  store_le(reinterpret_cast<uint8_t *>(&b[b.size() - 8]), sum.value(), 8);
  e2e::write_bytes(path, b);
  auto restored = make_film();
  CheckpointInfo info = make_info();
  const Status read = read_checkpoint(*restored, path, info);
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_TRUE(info.states.empty());
  EXPECT_EQ(sum_bits(*restored, "beauty"), sum_bits(*film, "beauty"));
}

TEST(CheckpointFormat, PeekReadsTheHeaderOnly) {
  TestDir dir;
  auto film = make_film();
  for (uint64_t i = 1; i <= 4; ++i) add_iteration(*film, i);
  const std::string path = dir.file("c.ckpt");
  ASSERT_TRUE(write_checkpoint(*film, path, make_info()).ok());
  const auto peeked = peek_checkpoint(path);
  ASSERT_TRUE(peeked.ok()) << peeked.error().message;
  EXPECT_EQ(peeked->iterations, 4u);
  EXPECT_EQ(peeked->seed, make_info().seed);
  EXPECT_EQ(peeked->integrator, make_info().integrator);
  EXPECT_EQ(peeked->fingerprint, make_info().fingerprint);
  EXPECT_EQ(peeked->seconds, make_info().seconds);
}

TEST(CheckpointFormat, ReplacesAnEarlierCheckpointWhole) {
  TestDir dir;
  const std::string path = dir.file("d.ckpt");
  e2e::write_bytes(path, "an earlier checkpoint");
  auto film = make_film();
  add_iteration(*film, 1);
  ASSERT_TRUE(write_checkpoint(*film, path, make_info()).ok());
  EXPECT_EQ(peek_checkpoint(path)->iterations, 1u);
  EXPECT_EQ(dir.temporaries(), std::vector<std::string>{});
}

TEST(CheckpointFormat, RefusesAFilmWithUnmergedSplats) {
  TestDir dir;
  auto film = make_film();
  add_iteration(*film, 1);
  const float v[3] = {1, 2, 3};
  film->splat(0, film->register_element("lightmix.key", 3, Film::kSplat), 0.5f, 0.5f, v);  // not merged
  const std::string path = dir.file("e.ckpt");
  const Status s = write_checkpoint(*film, path, make_info());
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find(path), std::string::npos) << s.error().message;
  EXPECT_NE(s.error().message.find("splats"), std::string::npos) << s.error().message;
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(CheckpointFormat, UnwritableDirectoryIsAnErrorNamingThePath) {
  TestDir dir;
  auto film = make_film();
  add_iteration(*film, 1);
  const std::string path = dir.file("missing/f.ckpt");
  const Status s = write_checkpoint(*film, path, make_info());
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find(path), std::string::npos) << s.error().message;
}

TEST(CheckpointFormat, ContentHashIsStableAndSensitive) {
  EXPECT_EQ(content_hash("render:\n  seed: 7\n"), content_hash("render:\n  seed: 7\n"));
  EXPECT_NE(content_hash("render:\n  seed: 7\n"), content_hash("render:\n  seed: 8\n"));
  EXPECT_NE(content_hash(""), content_hash(std::string(1, '\0')));  // the length counts
  EXPECT_EQ(content_hash("x").size(), 16u);
}

}  // namespace checkpoint_format_test
}  // namespace nimbus
