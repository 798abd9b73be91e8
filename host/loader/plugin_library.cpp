#include "loader/plugin_library.hpp"

#include <dlfcn.h>

#include <cstddef>

#include "loader/plugin_version.hpp"

namespace nimbus {
namespace {

// struct_size and abi sit at offsets frozen across all majors; `abi` is readable once struct_size covers it.
constexpr uint32_t kAbiEnd = offsetof(nimbus_entry_t, abi) + sizeof(nimbus_version_t);

std::string last_dlerror() {
  const char *e = dlerror();
  return e != nullptr ? e : "unknown error";
}

std::string missing_functions(const nimbus_entry_t &e) {
  std::string names;
  auto note = [&](bool missing, const char *name) {
    if (!missing) return;
    if (!names.empty()) names += ", ";
    names += name;
  };
  note(e.init == nullptr, "init");
  note(e.deinit == nullptr, "deinit");
  note(e.count == nullptr, "count");
  note(e.descriptor == nullptr, "descriptor");
  note(e.create == nullptr, "create");
  return names;
}

}  // namespace

OpenedLibrary open_library(const std::string &path, nimbus_version_t host_abi) {
  OpenedLibrary lib;
  dlerror();  // clear any stale error so the one reported belongs to this call
  // NOW: a missing symbol fails here with a message instead of crashing at first use. LOCAL: libraries
  // bundling their own zlib/OpenEXR/... cannot interpose on each other. Never GLOBAL or DEEPBIND.
  lib.handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (lib.handle == nullptr) {
    lib.error = "not a loadable shared library (" + last_dlerror() + ")";
    return lib;
  }
  dlerror();
  void *symbol = dlsym(lib.handle, NIMBUS_PLUGIN_ENTRY_SYMBOL);
  if (symbol == nullptr) {
    lib.error = "no entry symbol '" NIMBUS_PLUGIN_ENTRY_SYMBOL "' (not a Nimbus plugin)";
    return lib;
  }
  OpenedLibrary read = read_entry(reinterpret_cast<nimbus_plugin_entry_fn>(symbol), host_abi);
  read.handle = lib.handle;
  return read;
}

OpenedLibrary read_entry(nimbus_plugin_entry_fn entry_fn, nimbus_version_t host_abi) {
  OpenedLibrary lib;
  const nimbus_entry_t *entry = entry_fn();
  if (entry == nullptr) {
    lib.error = NIMBUS_PLUGIN_ENTRY_SYMBOL "() returned NULL";
    return lib;
  }
  if (entry->struct_size < kAbiEnd) {
    lib.error = "entry struct_size " + std::to_string(entry->struct_size) + " is too small to hold a version";
    return lib;
  }
  lib.abi = entry->abi;
  // The version decides first: a plugin of another major may legitimately have a different entry layout.
  if (auto why = check_abi(entry->abi, host_abi)) {
    lib.error = std::move(*why);
    return lib;
  }
  if (entry->struct_size < kEntrySize10) {
    lib.error = "entry struct_size " + std::to_string(entry->struct_size) +
                " is smaller than SDK ABI 1.0's " + std::to_string(kEntrySize10) + " (built for SDK ABI " +
                format_version(entry->abi) + ", host provides " + format_version(host_abi) + ")";
    return lib;
  }
  if (auto missing = missing_functions(*entry); !missing.empty()) {
    lib.error = "entry has NULL functions: " + missing;
    return lib;
  }
  lib.entry = entry;
  return lib;
}

}  // namespace nimbus
