#include "abi/run_state.hpp"

namespace nimbus {

RunState::RunState(uint32_t width, uint32_t height, uint32_t threads, uint64_t seed_)
    : film(width, height), seed(seed_) {
  const int n = threads > 0 ? int(threads) : tbb::this_task_arena::max_concurrency();
  arena = std::make_unique<tbb::task_arena>(n);
  worker_count = uint32_t(n);
  ray_counters.resize(size_t(n));
  worker_tiles.resize(size_t(n));
  main_thread = std::this_thread::get_id();
}

}  // namespace nimbus
