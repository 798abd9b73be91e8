// Fetching a plugin's interface table and checking it is large enough to call (sdk-idioms.md §1.3).
// The minimum is the size the table had in SDK 1.0, never sizeof() of the live struct: tables only grow
// within a major, so a plugin built against 1.0 carries a smaller table than a 1.1 host's headers
// declare, and must still load. Members appended later are read only when NIMBUS_HAS_MEMBER says the
// plugin's table holds them.
#pragma once

#include <nimbus/integrator.h>
#include <nimbus/light_sampler.h>

#include <cstddef>
#include <string>

#include "core/expected.hpp"
#include "loader/plugin_registry.hpp"

namespace nimbus {

// nimbus_integrator_v1_t at SDK 1.0: every hook through end_render is mandatory.
inline constexpr size_t kIntegratorSize10 =
    offsetof(nimbus_integrator_v1_t, end_render) + sizeof(nimbus_integrator_v1_t::end_render);
// nimbus_light_sampler_v1_t: record and end_iteration (both 1.0) are optional, so a table may end
// before them; the host checks NIMBUS_HAS_MEMBER (and NULL) before calling either.
inline constexpr size_t kLightSamplerMinSize = offsetof(nimbus_light_sampler_v1_t, record);

// The literal 1.0 numbers on x86-64 (tests/abi/layout_1_0.c): a reordered header cannot move the
// minimum unnoticed.
#if defined(__x86_64__)
static_assert(kIntegratorSize10 == 56 && kLightSamplerMinSize == 40);
#endif

// Interface `iface` at revision 1 of `plugin`, or an error naming the plugin (by `id`, the validated
// descriptor's), the interface and both sizes when the plugin lacks it or its table is smaller than
// `min_size` bytes.
template <class Table>
Expected<const Table *> interface_of(const nimbus_plugin_t *plugin, const std::string &id, const char *iface,
                                     size_t min_size) {
  const auto *t = static_cast<const Table *>(plugin->get_interface(plugin, iface, 1));
  const std::string who = "plugin '" + id + "'";
  if (!t) return Error{who + " does not provide " + iface + "@1"};
  if (t->struct_size < min_size)
    return Error{who + ": " + iface + "@1 table is too small (" + std::to_string(t->struct_size) +
                 " bytes; SDK 1.0 tables have at least " + std::to_string(min_size) + ")"};
  return t;
}

template <class Table>
Expected<const Table *> interface_of(const PluginHandle &plugin, const char *iface, size_t min_size) {
  return interface_of<Table>(plugin.get(), plugin.id(), iface, min_size);
}

}  // namespace nimbus
