// The progressive loop: iteration after iteration (begin_iteration, every tile in parallel, splats merged,
// end_iteration) until the job's stopping rules, cancellation or a plugin failure; checkpoints between
// iterations and progress after each, and a last checkpoint when it stops. Whatever ends it, end_render is
// called and the film holds only complete iterations: an iteration a tile failed in is undone.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

#include <nimbus/nimbus.h>

#include "abi/run_state.hpp"
#include "film/iteration_undo.hpp"
#include "render/bind_plugins.hpp"
#include "render/render_checkpoint.hpp"
#include "render/render_job.hpp"
#include "render/render_session.hpp"
#include "render/tiling.hpp"

namespace nimbus {

struct LoopOutcome {
  uint64_t resumed_from = 0;           // iterations the film held before the loop
  uint64_t done = 0;                   // iterations it holds after
  double seconds = 0;                  // render time since this run started or resumed
  double first_iteration_seconds = 0;  // of this run's first iteration (0 when none finished)
  bool cancelled = false;
  bool reached_target = false;
  double estimated_error = -1;  // the last estimate with an error target
  nimbus_status_t failure = NIMBUS_OK;
  std::string failure_hook;    // the integrator hook that failed
  Status checkpointed = Ok{};  // the final checkpoint's save

  // "error", "cancel", "target_error", "iterations" or "time" (the EXR's nimbus:stopped_by).
  std::string stopped_by(const StopRules &stop) const;
};

// Renders into run.film (and run.error_estimate when there is one), polling *run.cancel between
// iterations. run.tile_started holds one flag per tile of `tiling`; `undo` was made from the set-up film.
LoopOutcome run_progressive_loop(const RenderJob &job, const BoundPlugins &plugins, RunState &run,
                                 const Tiling &tiling, IterationUndo &undo, RenderCheckpoint &checkpoint,
                                 const ProgressFn &progress, const MessageFn &message);

}  // namespace nimbus
