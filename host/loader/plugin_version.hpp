// The SDK ABI compatibility rule (sdk-idioms.md §1.2), kept pure so it can be tested exhaustively.
#pragma once

#include <nimbus/version.h>

#include <optional>
#include <string>

namespace nimbus {

// The ABI this host was compiled against.
inline constexpr nimbus_version_t kHostAbi = NIMBUS_ABI_VERSION_INIT;

// "1.4.0": major.minor.patch; `reserved` is not part of a version.
std::string format_version(nimbus_version_t v);

// Why a plugin built for `plugin` cannot load into a host providing `host`, or nullopt when it can.
// Loads iff the majors are equal and the plugin's minor is not newer; in 0.x the minors must be equal
// because 0.x makes no compatibility promise. Patch never matters. The reason names both versions, e.g.
// "built for SDK ABI 1.4.0, host provides 1.3.2 (newer minor)".
std::optional<std::string> check_abi(nimbus_version_t plugin, nimbus_version_t host);

}  // namespace nimbus
