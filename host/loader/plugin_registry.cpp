#include "loader/plugin_registry.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "loader/plugin_descriptor.hpp"
#include "loader/plugin_library.hpp"
#include "loader/plugin_status.hpp"
#include "loader/plugin_version.hpp"

namespace nimbus {
namespace fs = std::filesystem;
namespace {

// A count() beyond this is a corrupt library, not a plugin collection; do not walk billions of indices.
constexpr uint32_t kMaxPluginsPerLibrary = 1024;

constexpr uint32_t kPluginSize10 =
    offsetof(nimbus_plugin_t, get_interface) + sizeof(nimbus_plugin_t::get_interface);

void stderr_sink(int level, const std::string &line) {
  if (level < NIMBUS_LOG_WARNING) return;
  std::fprintf(stderr, "nimbus: %s: %s\n", level >= NIMBUS_LOG_ERROR ? "error" : "warning", line.c_str());
}

bool is_shared_object_name(const fs::path &p) {
  const std::string name = p.filename().string();
  return name.size() > 3 && name.ends_with(".so");
}

}  // namespace

bool PluginRecord::has_feature(std::string_view feature) const {
  return std::find(features.begin(), features.end(), feature) != features.end();
}

PluginRegistry::PluginRegistry(LogSink sink) : sink_(sink ? std::move(sink) : LogSink(stderr_sink)) {}

PluginRegistry::~PluginRegistry() { deinit_all(); }

void PluginRegistry::log(int level, const std::string &line) const { sink_(level, line); }

void PluginRegistry::discover(const std::vector<std::string> &dirs, const nimbus_host_t *host_for_checks) {
  for (const auto &dir : dirs) discover_dir(dir, host_for_checks);
}

void PluginRegistry::discover_dir(const std::string &dir, const nimbus_host_t *host) {
  std::error_code ec;
  fs::path root = fs::absolute(dir, ec).lexically_normal();
  if (!root.has_filename()) root = root.parent_path();  // "/a/b/" -> "/a/b" for readable messages
  if (!fs::is_directory(root, ec)) {
    log(NIMBUS_LOG_WARNING, "plugin directory " + root.string() + " does not exist or is not a directory");
    return;
  }
  std::vector<fs::path> files;
  for (fs::directory_iterator it(root, ec), end; !ec && it != end; it.increment(ec)) {
    // is_regular_file follows symlinks, so libfoo.so -> libfoo.so.1 counts; subdirectories never do.
    if (is_shared_object_name(it->path()) && it->is_regular_file(ec)) files.push_back(it->path());
  }
  if (ec) {
    log(NIMBUS_LOG_WARNING, "cannot read plugin directory " + root.string() + ": " + ec.message());
    return;
  }
  // Filename order, so which of two duplicates wins does not depend on the file system.
  std::sort(files.begin(), files.end(),
            [](const fs::path &a, const fs::path &b) { return a.filename() < b.filename(); });
  for (const auto &f : files) load_file(f.string(), host);
}

void PluginRegistry::load_file(const std::string &path, const nimbus_host_t *host) {
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(path, ec);
  if (!seen_files_.insert(ec ? path : canonical.string()).second) return;
  load_opened(path, open_library(path, kHostAbi), host);
}

void PluginRegistry::load_opened(const std::string &path, const OpenedLibrary &opened,
                                 const nimbus_host_t *host) {
  PluginRecord base;
  base.path = path;
  if (opened.abi) {
    base.has_abi = true;
    base.abi = *opened.abi;
  }
  if (opened.handle != nullptr) {
    // A hard link or bind mount of a library already opened: dlopen hands back the same handle, and its
    // plugins are already registered (or refused) under the first path.
    auto [it, fresh] = handles_.emplace(opened.handle, path);
    if (!fresh) {
      refuse(std::move(base), "same library as " + it->second + ", already opened");
      return;
    }
  }
  if (!opened.error.empty()) {
    refuse(std::move(base), opened.error);
    return;
  }

  const nimbus_entry_t *entry = opened.entry;
  const nimbus_status_t init = entry->init(path.c_str());
  if (init != NIMBUS_OK) {
    refuse(std::move(base), "init failed: " + status_text(init));
    return;
  }
  const Library lib{path, opened.handle, entry};
  if (load_plugins(lib, libraries_.size(), host) == 0) {
    entry->deinit();  // nothing of it is kept, so release what init acquired now
    return;
  }
  libraries_.push_back(lib);
}

size_t PluginRegistry::load_plugins(const Library &lib, size_t library_index, const nimbus_host_t *host) {
  PluginRecord base;
  base.path = lib.path;
  base.has_abi = true;
  base.abi = lib.entry->abi;
  const uint32_t count = lib.entry->count();
  if (count == 0) {
    refuse(std::move(base), "library provides no plugins (count() returned 0)");
    return 0;
  }
  if (count > kMaxPluginsPerLibrary) {
    refuse(std::move(base), "count() returned " + std::to_string(count) + ", more than " +
                                std::to_string(kMaxPluginsPerLibrary));
    return 0;
  }
  size_t accepted = 0;
  for (uint32_t i = 0; i < count; ++i) {
    PluginRecord rec = base;
    DescriptorResult read = read_descriptor(lib.entry->descriptor(i), i);
    if (!read.copy) {
      refuse(std::move(rec), read.error);
      continue;
    }
    DescriptorCopy &d = *read.copy;
    rec.has_descriptor = true;
    rec.id = d.id;
    rec.name = d.name;
    rec.vendor = d.vendor;
    rec.kind = d.kind;
    rec.version = d.version;
    rec.features = d.features;
    rec.required_services = d.required_services;
    rec.options = d.options;
    if (auto dup = by_id_.find(d.id); dup != by_id_.end()) {
      refuse(std::move(rec),
             "duplicate plugin id '" + d.id + "', already provided by " + records_[dup->second.record].path);
      continue;
    }
    // Refuse now rather than mid-render: a plugin cannot work without the services it declares mandatory.
    if (auto missing = check_required_services(d, host)) {
      refuse(std::move(rec), *missing);
      continue;
    }
    rec.loaded = true;
    rec.status = "loaded";
    by_id_[d.id] = Loaded{library_index, records_.size()};
    log(NIMBUS_LOG_INFO, "loaded " + lib.path + ": " + kind_name(d.kind) + " '" + d.id + "' " +
                             format_version(d.version) + " (SDK ABI " + format_version(rec.abi) + ")");
    records_.push_back(std::move(rec));
    ++accepted;
  }
  return accepted;
}

void PluginRegistry::refuse(PluginRecord record, const std::string &reason) {
  record.loaded = false;
  record.status = reason;
  log(NIMBUS_LOG_WARNING, "refused " + record.path + ": " + reason);
  records_.push_back(std::move(record));
}

const PluginRecord *PluginRegistry::find(const std::string &id) const {
  auto it = by_id_.find(id);
  // Scenes say `integrator: pt` for the first-party "nimbus.pt".
  if (it == by_id_.end()) it = by_id_.find("nimbus." + id);
  return it == by_id_.end() ? nullptr : &records_[it->second.record];
}

std::vector<std::string> PluginRegistry::loaded_ids(nimbus_plugin_kind_t kind) const {
  std::vector<std::string> ids;
  for (const auto &[id, loaded] : by_id_) {
    if (records_[loaded.record].kind == kind) ids.push_back(id);  // std::map: already sorted
  }
  return ids;
}

Expected<const nimbus_plugin_t *> PluginRegistry::create(const std::string &id,
                                                         nimbus_plugin_kind_t expected_kind,
                                                         const nimbus_host_t *host) {
  const PluginRecord *rec = find(id);
  if (rec == nullptr) {
    std::string available;
    for (const auto &other : loaded_ids(expected_kind)) available += (available.empty() ? "" : ", ") + other;
    return Error{"no plugin with id '" + id + "' is loaded (" +
                 (available.empty() ? "no " + kind_plural(expected_kind) + " are loaded"
                                    : "available " + kind_plural(expected_kind) + ": " + available) +
                 ")"};
  }
  const std::string who = "plugin '" + rec->id + "'";
  if (rec->kind != expected_kind) {
    return Error{who + " is " + kind_with_article(rec->kind) + ", not " + kind_with_article(expected_kind)};
  }
  const nimbus_entry_t *entry = libraries_[by_id_.at(rec->id).library].entry;

  const nimbus_plugin_t *plugin = nullptr;
  const nimbus_status_t created = entry->create(rec->id.c_str(), host, &plugin);
  if (created != NIMBUS_OK) return Error{who + " could not be created: " + status_text(created)};
  if (plugin == nullptr) return Error{who + " could not be created (create returned no instance)"};
  const bool can_destroy = NIMBUS_HAS_MEMBER(plugin, nimbus_plugin_t, destroy) && plugin->destroy != nullptr;
  if (plugin->struct_size < kPluginSize10 || plugin->init == nullptr || plugin->get_interface == nullptr ||
      !can_destroy) {
    if (can_destroy) plugin->destroy(plugin);
    return Error{who + " returned a malformed instance (struct_size " + std::to_string(plugin->struct_size) +
                 ", SDK ABI 1.0 needs " + std::to_string(kPluginSize10) + " and non-NULL functions)"};
  }
  const nimbus_status_t init = plugin->init(plugin);
  if (init != NIMBUS_OK) {
    plugin->destroy(plugin);
    return Error{who + " failed to initialise: " + status_text(init)};
  }
  live_.push_back(plugin);
  return plugin;
}

Expected<PluginHandle> PluginRegistry::instantiate(const std::string &id, nimbus_plugin_kind_t expected_kind,
                                                   const nimbus_host_t *host) {
  auto created = create(id, expected_kind, host);
  if (!created) return created.error();
  return PluginHandle(*this, created.value(), *find(id));
}

void PluginRegistry::destroy(const nimbus_plugin_t *plugin) {
  if (plugin == nullptr) return;
  auto it = std::find(live_.begin(), live_.end(), plugin);
  if (it == live_.end()) {
    // Calling through a stale or foreign pointer would crash inside plugin code; report the host bug.
    log(NIMBUS_LOG_ERROR, "destroy of a plugin instance this registry did not create or already destroyed");
    return;
  }
  live_.erase(it);
  plugin->destroy(plugin);
}

void PluginRegistry::deinit_all() {
  // deinit ends descriptor and instance lifetimes, so instances go first, newest first.
  while (!live_.empty()) {
    const nimbus_plugin_t *plugin = live_.back();
    live_.pop_back();
    plugin->destroy(plugin);
  }
  for (auto it = libraries_.rbegin(); it != libraries_.rend(); ++it) it->entry->deinit();
  libraries_.clear();
  by_id_.clear();  // nothing can be created from a deinitialised library
}

}  // namespace nimbus
