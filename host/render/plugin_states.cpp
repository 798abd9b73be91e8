#include "render/plugin_states.hpp"

#include <new>

#include "loader/plugin_status.hpp"

namespace nimbus {
namespace {

// The host side of nimbus_state_writer_t: appends to a byte vector.
nimbus_status_t append(const nimbus_state_writer_t *w, const void *bytes, uint64_t size) {
  auto *out = static_cast<std::vector<uint8_t> *>(w->host_data);
  if (size > 0 && !bytes) return NIMBUS_E_INVALID_ARG;
  try {
    const auto *b = static_cast<const uint8_t *>(bytes);
    out->insert(out->end(), b, b + size);
  } catch (const std::bad_alloc &) {
    return NIMBUS_E_NO_MEMORY;
  } catch (const std::length_error &) {
    return NIMBUS_E_NO_MEMORY;
  }
  return NIMBUS_OK;
}

}  // namespace

PluginStates::PluginStates(const BoundPlugins &plugins) {
  for (const PluginHandle *h : {&plugins.integrator, &plugins.sampler, &plugins.guide}) {
    const nimbus_plugin_t *p = h->get();
    if (!p) continue;
    const auto *t =
        static_cast<const nimbus_render_state_v1_t *>(p->get_interface(p, NIMBUS_IFACE_RENDER_STATE, 1));
    // Both members came with revision 1: a smaller table is not one.
    if (t && t->struct_size >= sizeof(nimbus_render_state_v1_t) && t->save && t->restore)
      stateful_.push_back({h->id(), p, t});
  }
}

Expected<std::vector<PluginState>> PluginStates::save(uint64_t iterations) const {
  std::vector<PluginState> out;
  for (const Stateful &s : stateful_) {
    PluginState st{s.id, {}};
    const nimbus_state_writer_t writer{sizeof(nimbus_state_writer_t), 0, &st.bytes, append};
    if (nimbus_status_t r = s.iface->save(s.plugin, iterations, &writer); r != NIMBUS_OK)
      return Error{"plugin '" + s.id + "' could not save its state: " + status_text(r)};
    out.push_back(std::move(st));
  }
  return out;
}

void PluginStates::restore(const std::vector<PluginState> &states, uint64_t iterations,
                           const MessageFn &warn) const {
  const std::string consequence =
      ": it continues from a fresh start, so the image stays consistent but differs from an uninterrupted "
      "render's";
  for (const Stateful &s : stateful_) {
    const PluginState *saved = nullptr;
    for (const PluginState &st : states)
      if (st.plugin == s.id) saved = &st;
    if (!saved) {
      if (warn)
        warn(NIMBUS_LOG_WARNING, "the checkpoint holds no state of plugin '" + s.id + "'" + consequence);
      continue;
    }
    if (nimbus_status_t r = s.iface->restore(s.plugin, iterations, saved->bytes.data(), saved->bytes.size());
        r != NIMBUS_OK && warn)
      warn(NIMBUS_LOG_WARNING,
           "plugin '" + s.id + "' could not read its saved state (" + status_text(r) + ")" + consequence);
  }
}

}  // namespace nimbus
