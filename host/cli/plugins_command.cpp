// `nimbus plugins`: every library found on the search path, with its descriptor and load status; with
// --options ID, the options one plugin declares.
#include <cstdio>
#include <cstring>

#include "abi/host_services.hpp"
#include "cli/commands.hpp"
#include "loader/plugin_descriptor.hpp"
#include "loader/plugin_registry.hpp"

namespace nimbus::cli {
namespace {

constexpr const char *kHelp =
    "usage: nimbus plugins [--options ID]\n"
    "\n"
    "Lists every plugin library found in the search path: id, kind, version, path and status.\n"
    "Search path: $NIMBUS_PLUGIN_PATH (colon-separated), then the build tree's lib/nimbus/plugins,\n"
    "then <prefix>/lib/nimbus/plugins. Exits 1 if any library was refused.\n"
    "\n"
    "  --options ID   the options plugin ID declares (scene key render.NAME, flag --NAME): name, values,\n"
    "                 default and what it does\n";

int print_options(const PluginRegistry &registry, const std::string &id) {
  const PluginRecord *r = registry.find(id);
  if (!r) {
    std::fprintf(stderr, "nimbus plugins: no loaded plugin '%s' (run `nimbus plugins` for the list)\n",
                 id.c_str());
    return kExitFailure;
  }
  if (r->options.empty()) {
    std::printf("%s declares no options\n", r->id.c_str());
    return kExitOk;
  }
  std::printf("%s options (scene key render.NAME, flag --NAME):\n", r->id.c_str());
  std::printf("  %-20s %-24s %-10s %s\n", "NAME", "VALUES", "DEFAULT", "DESCRIPTION");
  for (const OptionDecl &o : r->options)
    std::printf("  %-20s %-24s %-10s %s\n", o.name.c_str(), describe_option_values(o).c_str(),
                o.default_value.empty() ? "\"\"" : o.default_value.c_str(), o.doc.c_str());
  return kExitOk;
}

}  // namespace

int plugins_command(const std::vector<std::string> &args) {
  std::string options_of;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string &a = args[i];
    if (a == "--help" || a == "-h") {
      std::fputs(kHelp, stdout);
      return kExitOk;
    }
    if (a == "--options" && i + 1 < args.size() && !args[i + 1].empty()) {
      options_of = args[++i];
      continue;
    }
    std::fprintf(stderr, "nimbus plugins: %s '%s'\n\n%s",
                 a == "--options" ? "expected a plugin id after" : "unknown option", a.c_str(), kHelp);
    return kExitUsage;
  }
  HostServices services(nullptr);
  PluginRegistry registry;
  const auto dirs = PluginRegistry::default_search_paths(executable_path());
  registry.discover(dirs, services.host());
  if (!options_of.empty()) return print_options(registry, options_of);
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
