#include "film/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace nimbus {
namespace {

namespace fs = std::filesystem;

// Only ever deletes a regular file: the temporary name could, however unlikely, belong to something
// the user made.
void remove_temporary(const std::string &tmp) {
  std::error_code ec;
  if (fs::is_regular_file(fs::symlink_status(tmp, ec))) fs::remove(tmp, ec);
}

// Without this, a power cut after the rename can leave an empty file under the new name on some file
// systems: the rename reaches the journal before the data.
bool flush_to_disk(const std::string &file) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool ok = ::fsync(fd) == 0;
  ::close(fd);
  return ok;
}

// The writers' own words for a full disk are often generic ("file output failed"): say it.
std::string with_space_left(const std::string &reason, const fs::path &dir) {
  std::error_code ec;
  const fs::space_info space = fs::space(dir.empty() ? fs::path(".") : dir, ec);
  if (ec || space.available >= (uint64_t(64) << 10)) return reason;
  return reason + " (the file system is full: " + std::to_string(space.available) + " bytes free)";
}

}  // namespace

Status write_atomically(const std::string &path,
                        const std::function<Status(const std::string &tmp_path)> &write) {
  const auto fail = [&](const std::string &reason) {
    return Error{"cannot write '" + path + "': " + reason};
  };
  if (path.empty()) return Error{"cannot write an image: empty output path"};
  const fs::path parent = fs::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty() && !fs::is_directory(parent, ec)) {
    return fail("directory '" + parent.string() + "' does not exist");
  }
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
  if (Status written = write(tmp); !written) {
    const std::string reason = with_space_left(written.error().message, parent);
    remove_temporary(tmp);
    return fail(reason);
  }
  if (!flush_to_disk(tmp)) {
    const std::string reason = with_space_left(std::strerror(errno), parent);
    remove_temporary(tmp);
    return fail("cannot flush '" + tmp + "': " + reason);
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    remove_temporary(tmp);
    return fail(reason);
  }
  return Ok{};
}

}  // namespace nimbus
