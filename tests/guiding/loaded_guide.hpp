// A guide as an integrator sees it (nimbus.guide.metropolis unless named otherwise): loaded from its shared
// library by the host's plugin registry, driven only through its C tables ("nimbus.iface.guiding" rev 2,
// "nimbus.iface.render-state" rev 1) with a tracer of plain C callbacks that log every path of a chain.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <nimbus/guiding.h>
#include <nimbus/render_state.h>

#include "loader/plugin_registry.hpp"
#include "metropolis_chain.hpp"

namespace nimbus::guide_test {

using Target = std::function<double(std::span<const float>)>;

// What the integrator saw of one chain: every traced u (dims floats each), kind and target value, and
// the credits in order. Path ids are indices.
struct ChainLog {
  ChainLog(const Target *target, uint32_t dims) : target(target), dims(dims) {}
  const Target *target;
  uint32_t dims;
  std::vector<float> u;
  std::vector<uint32_t> kinds;
  std::vector<double> targets;
  std::vector<std::pair<uint64_t, uint64_t>> credits;
  bool operator==(const ChainLog &o) const {
    return u == o.u && kinds == o.kinds && targets == o.targets && credits == o.credits;
  }
};

// The tracer's callbacks, as an integrator written in C has them: `user` is the chain's ChainLog.
inline double log_trace(void *user, const float *u, uint32_t kind, uint64_t *path) {
  ChainLog &log = *static_cast<ChainLog *>(user);
  *path = log.kinds.size();
  log.u.insert(log.u.end(), u, u + log.dims);
  log.kinds.push_back(kind);
  log.targets.push_back((*log.target)(std::span(u, log.dims)));
  return log.targets.back();
}
inline void log_credit(void *user, uint64_t path, uint64_t multiplicity) {
  static_cast<ChainLog *>(user)->credits.emplace_back(path, multiplicity);
}

// In which order, and on how many threads, a pass's run_chain calls are made.
enum class ChainOrder { serial, reversed_on_two_threads };

struct PassRun {
  nimbus_status_t status = NIMBUS_OK;  // the first failing call's
  std::vector<ChainLog> chains;
  std::vector<nimbus_guide_totals_t> totals;  // per chain, as run_chain reported it
  guide::ChainTotals sum;
  double acceptance() const { return sum.proposals ? double(sum.accepted) / double(sum.proposals) : 0.0; }
};

inline nimbus_guide_pass_t guide_pass(uint64_t seed, uint64_t pass, uint64_t budget, uint32_t chains,
                                      uint32_t dims) {
  return {{sizeof(nimbus_guide_pass_t), NIMBUS_S_TYPE_GUIDE_PASS, nullptr}, seed, pass, budget, chains, dims};
}

// Where the build puts first-party plugins (nimbus_add_plugin()); the host finds them there too.
inline std::string build_plugin_dir() { return std::string(NIMBUS_BINARY_DIR) + "/lib/nimbus/plugins"; }

class LoadedGuide {
 public:
  explicit LoadedGuide(std::string id = "nimbus.guide.metropolis",
                       const std::string &dir = build_plugin_dir());
  ~LoadedGuide() {
    if (plugin_) registry_.destroy(plugin_);
  }
  LoadedGuide(const LoadedGuide &) = delete;
  LoadedGuide &operator=(const LoadedGuide &) = delete;

  const nimbus_plugin_t *plugin() const { return plugin_; }
  const nimbus_guiding_v2_t &guide() const { return *guide_; }
  const PluginRecord *record() const { return registry_.find(id_); }
  // What the plugin logged through the host.
  std::vector<std::string> messages() const {
    const std::lock_guard lock(messages_->mutex);
    return messages_->lines;
  }

  nimbus_status_t prepare() const {
    nimbus_scene_info_t info{};
    info.header = {sizeof info, NIMBUS_S_TYPE_SCENE_INFO, nullptr};
    return guide_->prepare(plugin_, &info);
  }
  // begin_pass, run_chain for every chain in `order`, end_pass with the sums of the chains' totals.
  PassRun run_pass(const nimbus_guide_pass_t &pass, const Target &target,
                   ChainOrder order = ChainOrder::serial) const;
  // The render state (a guide that serves nimbus.iface.render-state).
  std::vector<uint8_t> save() const;
  nimbus_status_t restore(const std::vector<uint8_t> &bytes) const {
    return state_ ? state_->restore(plugin_, 1, bytes.data(), bytes.size()) : NIMBUS_E_UNSUPPORTED;
  }

 private:
  struct Messages {  // host_data: logged from any thread
    std::mutex mutex;
    std::vector<std::string> lines;
  };
  std::string id_;
  std::unique_ptr<Messages> messages_ = std::make_unique<Messages>();
  nimbus_host_t host_{};
  PluginRegistry registry_;
  const nimbus_plugin_t *plugin_ = nullptr;
  const nimbus_guiding_v2_t *guide_ = nullptr;
  const nimbus_render_state_v1_t *state_ = nullptr;
};

}  // namespace nimbus::guide_test
