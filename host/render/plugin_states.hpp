// The learnt state of the bound plugins that keep one (nimbus/render_state.h): saved with every
// checkpoint and handed back when a render resumes, so that a resumed render equals an uninterrupted one.
#pragma once

#include <nimbus/nimbus.h>

#include <string>
#include <vector>

#include "core/expected.hpp"
#include "film/checkpoint.hpp"
#include "render/bind_plugins.hpp"
#include "render/render_session.hpp"

namespace nimbus {

class PluginStates {
 public:
  PluginStates() = default;
  // The bound plugins (borrowed; they outlive this) that serve nimbus.iface.render-state@1.
  explicit PluginStates(const BoundPlugins &plugins);

  // [between iterations] Every such plugin's state after `iterations` iterations, or the error of the
  // first that fails (naming it).
  Expected<std::vector<PluginState>> save(uint64_t iterations) const;

  // [after begin_render, before the first iteration] Hands each plugin its saved state. A plugin without
  // one in `states` (a checkpoint written before it kept state) or that cannot read it continues from
  // what begin_render made, with a warning: the render stays consistent but is no longer identical to an
  // uninterrupted one.
  void restore(const std::vector<PluginState> &states, uint64_t iterations, const MessageFn &warn) const;

 private:
  struct Stateful {
    std::string id;
    const nimbus_plugin_t *plugin;
    const nimbus_render_state_v1_t *iface;
  };
  std::vector<Stateful> stateful_;
};

}  // namespace nimbus
