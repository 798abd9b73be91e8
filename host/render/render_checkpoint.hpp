// The checkpoint of one render (film/checkpoint.hpp has the file): restored before the first iteration
// when resuming, else an existing one is warned about before it is replaced; saved between iterations
// every job.checkpoint_interval_seconds and once more when the loop stops, each time with the plugins'
// learnt state (plugin_states.hpp).
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

#include "core/expected.hpp"
#include "film/checkpoint.hpp"
#include "film/film.hpp"
#include "render/plugin_states.hpp"
#include "render/render_job.hpp"
#include "render/render_session.hpp"

namespace nimbus {

class RenderCheckpoint {
 public:
  using Clock = std::chrono::steady_clock;

  // The checkpoint for `job` rendered by the bound plugins (their ids go into its fingerprint).
  RenderCheckpoint(const RenderJob &job, const std::string &integrator_id, const std::string &sampler_id,
                   const std::string &guide_id,
                   const std::vector<std::pair<std::string, std::string>> &integrator_options);

  // Resuming: the film's sums, iteration count and non-finite count from the file (or why they cannot
  // be). Otherwise a warning through `warn` (if any) when a checkpoint is about to be replaced.
  Status restore_or_warn(Film &film, const MessageFn &warn);

  // The plugins whose learnt state goes into every save (borrowed; outlives this). Without, none does.
  void keep_plugin_states(const PluginStates *states) { states_ = states; }
  // Resuming, after begin_render: hands the plugins the states the restored checkpoint holds.
  void restore_plugin_states(const MessageFn &warn) const {
    if (resume_ && states_) states_->restore(info_.states, info_.iterations, warn);
  }

  // This run's iterations (since it started or resumed) start at `t0`, with `done` iterations in the film.
  void start(uint64_t done, Clock::time_point t0);
  double session_seconds() const { return std::chrono::duration<double>(Clock::now() - t0_).count(); }
  // Render seconds of earlier sessions (of the checkpoint resumed; else 0).
  double previous_seconds() const { return previous_seconds_; }

  // Between iterations: saves when the interval has passed and the film holds unsaved iterations. A
  // failed periodic checkpoint costs only protection, not the render: it is a warning.
  void save_if_due(const Film &film, uint64_t done, const MessageFn &warn);
  // Saves when the film holds iterations the file lacks.
  Status save_if_behind(const Film &film, uint64_t done);

  // The path of the checkpoint on disk from this render (or the one resumed); empty when none.
  const std::string &saved_path() const { return saved_path_; }

 private:
  Status save(const Film &film, uint64_t done);

  std::string path_;
  double interval_;
  bool resume_;
  CheckpointInfo info_;
  double previous_seconds_ = 0;
  Clock::time_point t0_, last_save_;
  uint64_t saved_ = 0;  // iterations the checkpoint on disk holds
  std::string saved_path_;
  const PluginStates *states_ = nullptr;
};

}  // namespace nimbus
