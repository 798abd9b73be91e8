// Reading a checkpoint validates everything before touching the film: a missing, truncated, corrupted or
// foreign file, or one made for another render, is an error naming the path and the reason, and the film
// is left as it was.
#include <gtest/gtest.h>

#include <filesystem>

#include "checkpoint_fixture.hpp"
#include "e2e_support.hpp"

namespace nimbus {
namespace checkpoint_validation_test {

using e2e::read_bytes;
using e2e::TestDir;
using e2e::write_bytes;
using test::add_iteration;
using test::make_film;
using test::make_info;
using test::sum_bits;

// A valid checkpoint of 2 iterations of the default fixture film, and the tests' helpers around it.
class CheckpointValidation : public ::testing::Test {
 protected:
  void SetUp() override {
    auto film = make_film();
    ASSERT_TRUE(film);
    add_iteration(*film, 1);
    add_iteration(*film, 2);
    ASSERT_TRUE(write_checkpoint(*film, path_, make_info()).ok());
    bytes_ = read_bytes(path_);
    ASSERT_GT(bytes_.size(), 100u);
  }

  // Reads `path` into a fresh film; expects failure with a message naming the path and containing
  // `reason`, and the film untouched.
  void expect_refused(const std::string &path, const std::string &reason, CheckpointInfo info = make_info(),
                      const std::vector<std::string> &elements = {"albedo", "depth", "lightmix.key"},
                      uint32_t width = test::kWidth) {
    auto film = make_film(elements, width);
    ASSERT_TRUE(film);
    const auto before = sum_bits(*film, "beauty");
    const Status s = read_checkpoint(*film, path, info);
    ASSERT_FALSE(s.ok()) << "accepted; expected: " << reason;
    const std::string &m = s.error().message;
    EXPECT_NE(m.find("'" + path + "'"), std::string::npos) << m;
    EXPECT_NE(m.find(reason), std::string::npos) << m;
    EXPECT_EQ(film->iterations(), 0u);
    EXPECT_EQ(film->nonfinite_count(), 0u);
    EXPECT_EQ(sum_bits(*film, "beauty"), before);
  }

  // The valid file with `edit` applied, written beside it.
  std::string variant(const std::string &name, const std::function<void(std::string &)> &edit) {
    std::string b = bytes_;
    edit(b);
    const std::string p = dir_.file(name);
    write_bytes(p, b);
    return p;
  }

  TestDir dir_;
  const std::string path_ = dir_.file("valid.ckpt");
  std::string bytes_;
};

TEST_F(CheckpointValidation, TheValidFileIsAccepted) {
  auto film = make_film();
  CheckpointInfo info = make_info();
  const Status s = read_checkpoint(*film, path_, info);
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_EQ(film->iterations(), 2u);
}

TEST_F(CheckpointValidation, MissingFile) { expect_refused(dir_.file("none.ckpt"), "cannot open"); }

TEST_F(CheckpointValidation, TruncatedAnywhere) {
  // Inside the magic, the header, the strings, the element data and the checksum.
  for (size_t keep : {size_t(0), size_t(5), size_t(10), size_t(30), size_t(60), size_t(90), bytes_.size() / 2,
                      bytes_.size() - 9, bytes_.size() - 1}) {
    SCOPED_TRACE("kept " + std::to_string(keep) + " of " + std::to_string(bytes_.size()) + " bytes");
    const std::string p = variant("cut.ckpt", [&](std::string &b) { b.resize(keep); });
    expect_refused(p, keep < 8 ? "too short" : "truncated");
  }
}

TEST_F(CheckpointValidation, TruncationSaysWhere) {
  const std::string p = variant("cut.ckpt", [&](std::string &b) { b.resize(b.size() / 2); });
  auto film = make_film();
  CheckpointInfo info = make_info();
  const Status s = read_checkpoint(*film, p, info);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("inside the sums of element"), std::string::npos) << s.error().message;
}

TEST_F(CheckpointValidation, WrongMagic) {
  expect_refused(variant("magic.ckpt", [](std::string &b) { b[0] = 'X'; }), "not a Nimbus checkpoint");
  expect_refused(variant("exr.ckpt", [](std::string &b) { b.replace(0, 4, "\x76\x2f\x31\x01"); }),
                 "wrong magic number");
}

TEST_F(CheckpointValidation, UnsupportedVersion) {
  expect_refused(variant("v3.ckpt", [](std::string &b) { b[8] = 3; }), "format version 3 is not supported");
}

TEST_F(CheckpointValidation, AnyFlippedBitInTheDataIsCaught) {
  for (size_t at : {bytes_.size() / 3, bytes_.size() / 2, bytes_.size() - 20, bytes_.size() - 3}) {
    SCOPED_TRACE("byte " + std::to_string(at));
    expect_refused(variant("flip.ckpt", [&](std::string &b) { b[at] ^= 0x10; }), "checksum mismatch");
  }
}

TEST_F(CheckpointValidation, TrailingBytes) {
  expect_refused(variant("long.ckpt", [](std::string &b) { b += "extra"; }), "5 unexpected bytes");
}

TEST_F(CheckpointValidation, ImageSizeMismatch) {
  expect_refused(path_, "7x5 image; this render is 9x5", make_info(), {"albedo", "depth", "lightmix.key"}, 9);
}

TEST_F(CheckpointValidation, ElementSetMismatch) {
  expect_refused(path_, "holds the elements", make_info(), {"albedo", "lightmix.key"});
  expect_refused(path_, "holds the elements", make_info(), {"albedo", "depth", "lightmix.key", "normal"});
}

TEST_F(CheckpointValidation, IntegratorMismatch) {
  CheckpointInfo info = make_info();
  info.integrator = "nimbus.lt";
  expect_refused(path_, "made with integrator 'nimbus.pt'; this render uses 'nimbus.lt'", info);
}

TEST_F(CheckpointValidation, SeedMismatch) {
  CheckpointInfo info = make_info();
  info.seed = 8;
  expect_refused(path_, "seed 18364758544493064720; this render uses 8", info);
}

TEST_F(CheckpointValidation, FingerprintMismatchNamesTheFieldsThatDiffer) {
  CheckpointInfo info = make_info();
  info.fingerprint =
      "scene_hash=ffffffffffffffff\nresolution=7x5\nseed=18364758544493064720\nelements=albedo\n";
  expect_refused(path_, "scene_hash: checkpoint '0123456789abcdef', this render 'ffffffffffffffff'", info);
  info.fingerprint = make_info().fingerprint + "options=caustics:on\n";
  expect_refused(path_, "options: checkpoint '(none)', this render 'caustics:on'", info);
}

}  // namespace checkpoint_validation_test
}  // namespace nimbus
