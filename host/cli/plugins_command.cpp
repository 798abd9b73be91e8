// `nimbus plugins`: every library found on the search path, with its descriptor and load status.
#include <cstdio>
#include <cstring>

#include "abi/host_services.hpp"
#include "cli/commands.hpp"
#include "loader/plugin_descriptor.hpp"
#include "loader/plugin_registry.hpp"

namespace nimbus::cli {
namespace {

constexpr const char *kHelp =
    "usage: nimbus plugins\n"
    "\n"
    "Lists every plugin library found in the search path: id, kind, version, path and status.\n"
    "Search path: $NIMBUS_PLUGIN_PATH (colon-separated), then the build tree's lib/nimbus/plugins,\n"
    "then <prefix>/lib/nimbus/plugins. Exits 1 if any library was refused.\n";

}  // namespace

int plugins_command(const std::vector<std::string> &args) {
  for (const std::string &a : args) {
    if (a == "--help" || a == "-h") {
      std::fputs(kHelp, stdout);
      return kExitOk;
    }
    std::fprintf(stderr, "nimbus plugins: unknown option '%s'\n\n%s", a.c_str(), kHelp);
    return kExitUsage;
  }
  HostServices services(nullptr);
  PluginRegistry registry;
  const auto dirs = PluginRegistry::default_search_paths(executable_path());
  registry.discover(dirs, services.host());
  std::printf("search path:\n");
  for (const std::string &d : dirs) std::printf("  %s\n", d.c_str());
  std::printf("\n%-28s %-14s %-9s %-8s %s\n", "ID", "KIND", "VERSION", "STATUS", "PATH");
  bool refused = false;
  for (const PluginRecord &r : registry.records()) {
    char version[32] = "-";
    if (r.has_descriptor)
      std::snprintf(version, sizeof version, "%u.%u.%u", r.version.major, r.version.minor, r.version.patch);
    std::printf("%-28s %-14s %-9s %-8s %s\n", r.has_descriptor ? r.id.c_str() : "-",
                r.has_descriptor ? kind_name(r.kind).c_str() : "-", version, r.loaded ? "loaded" : "refused",
                r.path.c_str());
    if (!r.loaded) {
      std::printf("    reason: %s\n", r.status.c_str());
      refused = true;
    }
  }
  if (registry.records().empty()) std::printf("(no plugin libraries found)\n");
  return refused ? kExitFailure : kExitOk;
}

}  // namespace nimbus::cli
