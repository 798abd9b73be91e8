#include "loader/plugin_version.hpp"

namespace nimbus {

std::string format_version(nimbus_version_t v) {
  return std::to_string(v.major) + "." + std::to_string(v.minor) + "." + std::to_string(v.patch);
}

std::optional<std::string> check_abi(nimbus_version_t plugin, nimbus_version_t host) {
  const char *why = nullptr;
  if (plugin.major != host.major) {
    why = "different major";
  } else if (host.major == 0 && plugin.minor != host.minor) {
    why = "different minor in 0.x";
  } else if (plugin.minor > host.minor) {
    // A newer minor may rely on appended fields or service revisions this host lacks; refuse, never guess.
    why = "newer minor";
  }
  if (why == nullptr) return std::nullopt;
  return "built for SDK ABI " + format_version(plugin) + ", host provides " + format_version(host) + " (" +
         why + ")";
}

}  // namespace nimbus
