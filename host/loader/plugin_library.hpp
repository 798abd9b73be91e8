// Opening one plugin library and reading its entry table, calling nothing beyond the entry function
// (sdk-idioms.md §1.2, §1.8): a library built for another ABI is refused before any of its code that
// depends on the ABI runs.
#pragma once

#include <nimbus/plugin.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace nimbus {

// Size of nimbus_entry_t at SDK 1.0; later minors only append members after `create`.
inline constexpr uint32_t kEntrySize10 = offsetof(nimbus_entry_t, create) + sizeof(nimbus_entry_t::create);

struct OpenedLibrary {
  void *handle = nullptr;                 // from dlopen; never dlclosed in 1.x
  const nimbus_entry_t *entry = nullptr;  // set only when the library is usable
  std::optional<nimbus_version_t> abi;    // set whenever it could be read, also for a refused library
  std::string error;                      // refusal reason; empty when usable
};

// dlopen(path, RTLD_NOW | RTLD_LOCAL), look up and call nimbus_plugin_entry, then check struct_size, the
// ABI version and that the 1.0 function pointers are present. `path` must contain a '/' so that dlopen
// does not search the library path.
OpenedLibrary open_library(const std::string &path, nimbus_version_t host_abi);

// What open_library does once it has found the entry symbol: calls it and checks the table (no handle).
// Separate so that the fuzz target can hand it an entry built in-process (tests/fuzz/descriptor_fuzz.cpp).
OpenedLibrary read_entry(nimbus_plugin_entry_fn entry_fn, nimbus_version_t host_abi);

}  // namespace nimbus
