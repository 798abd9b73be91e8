#include "core/image_io.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <system_error>

#include "core/image_header.hpp"

namespace nimbus {
namespace fs = std::filesystem;
namespace {

constexpr const char *kModuleFile = "libnimbus_image_io.so";

// Where the module may be, in order: in the build tree or install prefix the running executable belongs
// to (<exe>/.. for bin/nimbus and tests/, <exe>/../.. for tests/fuzz/: lib/nimbus/host, or the configured
// library directory for a multiarch install), then the configured install location.
std::vector<fs::path> module_candidates() {
  // A directory of its own beside plugins/: a library directly under <libdir>/nimbus would make the
  // package run ldconfig for nothing.
  const fs::path module_dir = fs::path(NIMBUS_INSTALL_PLUGIN_DIR).parent_path() / "host";
  std::vector<fs::path> out;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path prefix = exe.parent_path().parent_path();
    for (const fs::path &p : {prefix, prefix.parent_path()})
      for (const fs::path &dir : {fs::path("lib/nimbus/host"), module_dir})
        out.push_back(p / dir / kModuleFile);
  }
  out.push_back(fs::path(NIMBUS_INSTALL_PREFIX) / module_dir / kModuleFile);
  // Once each (the configured library directory is often lib itself).
  std::vector<fs::path> unique;
  for (const fs::path &p : out)
    if (std::find(unique.begin(), unique.end(), p) == unique.end()) unique.push_back(p);
  return unique;
}

Expected<const ImageIo *> load() {
  std::error_code ec;
  const std::vector<fs::path> candidates = module_candidates();
  for (const fs::path &candidate : candidates) {
    if (!fs::is_regular_file(candidate, ec)) continue;
    const std::string path = candidate.lexically_normal().string();
    const auto fail = [&](const std::string &why) {
      return Error{"cannot load the image I/O module '" + path + "': " + why};
    };
    // Never closed: OpenImageIO keeps process-wide state until exit.
    void *library = dlopen(path.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (!library) return fail(dlerror());
    const auto entry = reinterpret_cast<ImageIoEntry>(dlsym(library, NIMBUS_IMAGE_IO_ENTRY));
    if (!entry) return fail("no " NIMBUS_IMAGE_IO_ENTRY " function");
    const ImageIo *io = entry(NIMBUS_VERSION_STRING);
    if (!io) return fail("built for another version of Nimbus than " NIMBUS_VERSION_STRING);
    return io;
  }
  std::string looked;
  for (const fs::path &candidate : candidates) looked += (looked.empty() ? "" : ", ") + candidate.string();
  return Error{std::string("cannot find the image I/O module ") + kModuleFile + " (looked for " + looked +
               ")"};
}

}  // namespace

Expected<const ImageIo *> image_io() {
  static const Expected<const ImageIo *> loaded = load();
  return loaded;
}

Expected<std::unique_ptr<ImageFile>> open_image_file(const std::string &path) {
  if (std::optional<std::string> problem = image_header_problem(path)) return Error{*problem};
  const Expected<const ImageIo *> io = image_io();
  if (!io) return io.error();
  return (*io)->open(path);
}

}  // namespace nimbus
