// A full disk and a read-only output directory, on a real small file system (a tmpfs the test mounts;
// CI runs as root, which may mount one). The atomic write (temporary, then rename) must leave the image
// already there untouched and no temporary behind; a full disk at the end of a render sends the new image
// to the temporary directory rather than lose it; a directory that cannot be written is refused before
// the render starts.
#include <gtest/gtest.h>
#include <sys/mount.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "e2e_support.hpp"

namespace nimbus::e2e {
namespace disk_full_test {

// A tmpfs of `kilobytes` mounted on a fresh directory for the test's lifetime.
class SmallFileSystem {
 public:
  explicit SmallFileSystem(const TestDir &dir, int kilobytes) : path_(dir.path() / "small") {
    std::filesystem::create_directories(path_);
    const std::string size = "size=" + std::to_string(kilobytes) + "k";
    if (::mount("tmpfs", path_.c_str(), "tmpfs", 0, size.c_str()) != 0)
      error_ = std::string("cannot mount a tmpfs on ") + path_.string() + ": " + std::strerror(errno) +
               " (the test needs root with CAP_SYS_ADMIN, as CI's container has)";
  }
  ~SmallFileSystem() {
    if (error_.empty()) ::umount2(path_.c_str(), MNT_DETACH);
  }
  const std::string &error() const { return error_; }
  std::string file(const std::string &name) const { return (path_ / name).string(); }
  bool make_read_only() {
    return ::mount(nullptr, path_.c_str(), nullptr, MS_REMOUNT | MS_RDONLY, "size=1m") == 0;
  }
  // Writes zeros until the file system refuses.
  void fill() {
    std::ofstream f(file("filler"), std::ios::binary);
    const std::string block(4096, '\0');
    while (f.write(block.data(), std::streamsize(block.size())) && f.flush()) {
    }
  }
  std::vector<std::string> temporaries() const {
    std::vector<std::string> out;
    for (const auto &e : std::filesystem::directory_iterator(path_))
      if (e.path().filename().string().find(".tmp-") != std::string::npos) out.push_back(e.path().string());
    return out;
  }

 private:
  std::filesystem::path path_;
  std::string error_;
};

TEST(DiskFull, ExistingImageUntouchedAndTheNewOneWrittenToTheTemporaryDirectory) {
  TestDir dir;
  SmallFileSystem fs(dir, 1024);
  ASSERT_TRUE(fs.error().empty()) << fs.error();
  const std::string out = fs.file("out.exr");
  ASSERT_TRUE(exited_with(run_nimbus({"render", scene("box.yaml"), "-o", out, "-q"}, dir), 0));
  const std::string exr = read_bytes(out), png = read_bytes(fs.file("out.png"));
  fs.fill();
  const ProcessResult r = run_nimbus({"render", scene("box.yaml"), "-o", out, "-q", "--seed", "9"}, dir);
  EXPECT_TRUE(r.exited && r.exit_code == 1) << r.describe();
  EXPECT_NE(r.err.find("cannot write '" + out + "'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the file system is full"), std::string::npos) << r.err;
  EXPECT_EQ(read_bytes(out), exr);
  EXPECT_EQ(read_bytes(fs.file("out.png")), png);
  EXPECT_TRUE(fs.temporaries().empty()) << ::testing::PrintToString(fs.temporaries());
  // The render is not lost: the message names where it went, and that image is the new render's.
  const size_t at = r.err.find("the image was written to ");
  ASSERT_NE(at, std::string::npos) << r.err;
  const std::string moved = r.err.substr(at + 25, r.err.find(" and ", at) - at - 25);
  const auto img = read_exr(moved);
  ASSERT_TRUE(img);
  EXPECT_EQ(recorded_seed(*img).value_or(0), 9u);
  std::filesystem::remove(moved);
  std::filesystem::remove(std::filesystem::path(moved).replace_extension(".png"));
}

TEST(DiskFull, ReadOnlyDirectoryIsRefusedBeforeTheRender) {
  TestDir dir;
  SmallFileSystem fs(dir, 1024);
  ASSERT_TRUE(fs.error().empty()) << fs.error();
  const std::string out = fs.file("out.exr");
  ASSERT_TRUE(exited_with(run_nimbus({"render", scene("box.yaml"), "-o", out, "-q"}, dir), 0));
  const std::string exr = read_bytes(out);
  ASSERT_TRUE(fs.make_read_only()) << std::strerror(errno);
  const ProcessResult r = run_nimbus({"render", scene("box.yaml"), "-o", out, "--seed", "9"}, dir);
  EXPECT_TRUE(r.exited && r.exit_code == 1) << r.describe();
  EXPECT_NE(r.err.find("cannot write into"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("Read-only file system"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("iterations in"), std::string::npos) << "refused before rendering:\n" << r.err;
  EXPECT_EQ(read_bytes(out), exr);
}

}  // namespace disk_full_test
}  // namespace nimbus::e2e
