// Where plugins are looked for (sdk-idioms.md §1.9): the user's NIMBUS_PLUGIN_PATH first, then the build
// tree or install prefix the running executable belongs to, then the configured install location.
#include <cstdlib>
#include <filesystem>
#include <set>
#include <string_view>
#include <system_error>

#include "loader/plugin_registry.hpp"

namespace nimbus {
namespace fs = std::filesystem;
namespace {

class PathList {
 public:
  // `must_exist`: fallback locations are listed only when present; the user's are kept so that a
  // misspelt NIMBUS_PLUGIN_PATH entry is reported by discover() instead of silently ignored.
  void add(const fs::path &dir, bool must_exist) {
    std::error_code ec;
    fs::path p = fs::absolute(dir, ec).lexically_normal();
    if (ec) return;
    if (!p.has_filename()) p = p.parent_path();
    if (must_exist && !fs::is_directory(p, ec)) return;
    // Canonical key: the build tree's and prefix's directories, or a symlinked NIMBUS_PLUGIN_PATH entry,
    // are often the same directory, which must be scanned once.
    const fs::path key = fs::weakly_canonical(p, ec);
    if (seen_.insert(ec ? p.string() : key.string()).second) dirs_.push_back(p.string());
  }
  std::vector<std::string> take() { return std::move(dirs_); }

 private:
  std::vector<std::string> dirs_;
  std::set<std::string> seen_;
};

}  // namespace

std::vector<std::string> PluginRegistry::default_search_paths(const std::string &executable_path) {
  return search_paths(std::getenv("NIMBUS_PLUGIN_PATH"), executable_path);
}

std::vector<std::string> PluginRegistry::search_paths(const char *plugin_path_env,
                                                      const std::string &executable_path) {
  PathList list;
  if (plugin_path_env != nullptr) {
    std::string_view rest = plugin_path_env;
    while (!rest.empty()) {
      const size_t colon = rest.find(':');
      const std::string_view entry = rest.substr(0, colon);
      if (!entry.empty()) list.add(fs::path(entry), false);
      rest = colon == std::string_view::npos ? std::string_view{} : rest.substr(colon + 1);
    }
  }
  if (!executable_path.empty()) {
    std::error_code ec;
    // Canonical, so a symlink such as /usr/local/bin/nimbus -> /opt/nimbus/bin/nimbus finds /opt/nimbus.
    fs::path exe = fs::weakly_canonical(fs::absolute(executable_path, ec), ec);
    if (ec) exe = fs::absolute(executable_path, ec);
    // <exe>/.. is the build tree (<build>/bin/nimbus, plugins built into <build>/lib/nimbus/plugins) or a
    // possibly relocated install prefix (<prefix>/bin/nimbus); an install may use a multiarch libdir
    // (lib/x86_64-linux-gnu/nimbus/plugins), hence the configured plugin dir under it as well.
    const fs::path prefix = exe.parent_path().parent_path();
    list.add(prefix / "lib" / "nimbus" / "plugins", true);
    list.add(prefix / NIMBUS_INSTALL_PLUGIN_DIR, true);
  }
  // The configured install location; operator/ keeps NIMBUS_INSTALL_PLUGIN_DIR when it is absolute.
  list.add(fs::path(NIMBUS_INSTALL_PREFIX) / NIMBUS_INSTALL_PLUGIN_DIR, true);
  return list.take();
}

}  // namespace nimbus
