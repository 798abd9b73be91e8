// Plugin discovery and loading (sdk-idioms.md §1.2, §1.8, §1.9). The registry opens every *.so in the
// search directories, refuses incompatible or broken libraries with one warning line each while the rest
// load, and creates plugin instances by id. Main-thread only, like the entry functions it calls.
#pragma once

#include <nimbus/host.h>
#include <nimbus/plugin.h>

#include <functional>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/expected.hpp"
#include "loader/plugin_library.hpp"
#include "loader/plugin_options.hpp"

namespace nimbus {

// One file seen by discover(), or one plugin of a library that provides several (one record each).
struct PluginRecord {
  std::string path;    // absolute path of the library
  std::string status;  // "loaded", or the refusal reason as logged
  bool loaded = false;
  // Filled as far as they could be read before a refusal.
  bool has_abi = false;  // the entry table could be read
  nimbus_version_t abi{};
  bool has_descriptor = false;  // the fields below are a validated copy of the descriptor
  std::string id, name, vendor;
  nimbus_plugin_kind_t kind = 0;
  nimbus_version_t version{};
  std::vector<std::string> features;
  std::vector<std::string> required_services;
  std::vector<OptionDecl> options;  // declared options (SDK 1.2)

  bool has_feature(std::string_view feature) const;
};

class PluginHandle;

class PluginRegistry {
 public:
  // `level` is a NIMBUS_LOG_* value; `line` has no prefix and no newline.
  using LogSink = std::function<void(int level, const std::string &line)>;

  // The default sink prints warnings and errors to stderr as "nimbus: warning: <line>".
  explicit PluginRegistry(LogSink sink = {});
  ~PluginRegistry();  // destroys live instances, then deinit_all()
  PluginRegistry(const PluginRegistry &) = delete;
  PluginRegistry &operator=(const PluginRegistry &) = delete;

  // Each entry of NIMBUS_PLUGIN_PATH (colon-separated, empty entries skipped); then, for `executable_path`
  // at <dir>/bin/nimbus, <dir>/lib/nimbus/plugins (build tree or install prefix) and
  // <dir>/<NIMBUS_INSTALL_PLUGIN_DIR>; then NIMBUS_INSTALL_PREFIX/NIMBUS_INSTALL_PLUGIN_DIR. Deduplicated
  // by canonical path. Directories other than NIMBUS_PLUGIN_PATH's are listed
  // only if they exist, so a typo in the variable is still reported by discover().
  static std::vector<std::string> default_search_paths(const std::string &executable_path);
  // The same with the variable's value passed in (nullptr: unset).
  static std::vector<std::string> search_paths(const char *plugin_path_env,
                                               const std::string &executable_path);

  // Loads every regular file named *.so directly inside each directory, directories in order and files
  // by name. The first plugin per id wins. `host_for_checks` answers the required-service checks; NULL
  // provides no services. Files already seen (same canonical path or same loaded library) are skipped.
  void discover(const std::vector<std::string> &dirs, const nimbus_host_t *host_for_checks);

  // What discover() does with each library once open_library has read it: init, every descriptor validated
  // and its plugin registered or refused, each refusal one warning line. Public so that the fuzz target
  // can hand it a library built in-process (tests/fuzz/descriptor_fuzz.cpp).
  void load_opened(const std::string &path, const OpenedLibrary &opened, const nimbus_host_t *host);

  const std::vector<PluginRecord> &records() const { return records_; }
  // The loaded plugin `id`, or "nimbus." + id as a short name; nullptr if neither is loaded.
  const PluginRecord *find(const std::string &id) const;
  // Ids of loaded plugins of `kind`, sorted.
  std::vector<std::string> loaded_ids(nimbus_plugin_kind_t kind) const;

  // Creates and initialises plugin `id` (short names allowed) of `expected_kind` for `host`, which must
  // outlive the instance. Release with destroy().
  Expected<const nimbus_plugin_t *> create(const std::string &id, nimbus_plugin_kind_t expected_kind,
                                           const nimbus_host_t *host);
  void destroy(const nimbus_plugin_t *plugin);
  // create() with the instance owned by the handle, which also carries the validated descriptor copy.
  Expected<PluginHandle> instantiate(const std::string &id, nimbus_plugin_kind_t expected_kind,
                                     const nimbus_host_t *host);

  // Calls deinit once for each library whose init succeeded and that was kept; never dlcloses (1.x).
  // Instances must have been destroyed first. Idempotent.
  void deinit_all();

 private:
  struct Library {
    std::string path;
    void *handle = nullptr;
    const nimbus_entry_t *entry = nullptr;
  };
  struct Loaded {
    size_t library = 0;  // index into libraries_
    size_t record = 0;   // index into records_
  };

  void discover_dir(const std::string &dir, const nimbus_host_t *host);
  void load_file(const std::string &path, const nimbus_host_t *host);
  // Reads the plugins of an initialised library; returns how many were accepted.
  size_t load_plugins(const Library &lib, size_t library_index, const nimbus_host_t *host);
  void refuse(PluginRecord record, const std::string &reason);
  void log(int level, const std::string &line) const;

  LogSink sink_;
  std::vector<PluginRecord> records_;
  std::vector<Library> libraries_;         // initialised and kept; deinit_all() walks these
  std::map<std::string, Loaded> by_id_;    // loaded plugins
  std::set<std::string> seen_files_;       // canonical paths
  std::map<void *, std::string> handles_;  // dlopen handle -> path it was first opened as
  std::vector<const nimbus_plugin_t *> live_;
};

// A plugin instance, destroyed through its registry when the handle goes (the registry must outlive it),
// and the loader's validated copy of its descriptor: the host reads the id and features from the copy,
// never again from the plugin's own descriptor.
class PluginHandle {
 public:
  PluginHandle() = default;
  PluginHandle(PluginRegistry &registry, const nimbus_plugin_t *plugin, PluginRecord record)
      : registry_(&registry), plugin_(plugin), record_(std::move(record)) {}
  PluginHandle(PluginHandle &&other) noexcept { *this = std::move(other); }
  PluginHandle &operator=(PluginHandle &&other) noexcept {
    if (this != &other) {
      reset();
      registry_ = std::exchange(other.registry_, nullptr);
      plugin_ = std::exchange(other.plugin_, nullptr);
      record_ = std::move(other.record_);
    }
    return *this;
  }
  ~PluginHandle() { reset(); }

  const nimbus_plugin_t *get() const { return plugin_; }
  const PluginRecord &record() const { return record_; }
  const std::string &id() const { return record_.id; }

 private:
  void reset() {
    if (plugin_) registry_->destroy(plugin_);
    plugin_ = nullptr;
  }

  PluginRegistry *registry_ = nullptr;
  const nimbus_plugin_t *plugin_ = nullptr;
  PluginRecord record_;
};

}  // namespace nimbus
