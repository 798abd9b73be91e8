// Parallel loops for plugin code: a ParallelFor is any runner of fn(i) over [0, count). Plugins get one
// on the host's task arena from host_parallel_for (no private thread pools, sdk-idioms.md 1.7); tests
// pass serial_for or threads of their own. Requires C++17.
#pragma once

#include <algorithm>
#include <cstddef>
#include <functional>

#include <nimbus/host.h>

namespace nimbus::sdk {

// Runs fn(i) for i in [0, count), possibly concurrently.
using ParallelFor = std::function<void(size_t count, const std::function<void(size_t)> &fn)>;

inline void serial_for(size_t count, const std::function<void(size_t)> &fn) {
  for (size_t i = 0; i < count; ++i) fn(i);
}

// A ParallelFor on the host's task service, one index per task grain: for loops of a few coarse items
// (chunks of a larger array). The tasks table and host are borrowed and must outlive the runner.
inline ParallelFor host_parallel_for(const nimbus_host_tasks_v1_t *tasks, const nimbus_host_t *host) {
  return [tasks, host](size_t count, const std::function<void(size_t)> &f) {
    const auto task = [](const nimbus_thread_ctx_t *, uint64_t b, uint64_t e, void *user) {
      const auto &fn = *static_cast<const std::function<void(size_t)> *>(user);
      for (uint64_t i = b; i < e; ++i) fn(size_t(i));
    };
    tasks->parallel_for(host, count, 1, task, const_cast<std::function<void(size_t)> *>(&f));
  };
}

// Runs fn(begin, end) over [0, n) in ranges of `chunk`, the ranges possibly concurrently.
template <class F>
void parallel_ranges(const ParallelFor &parallel, size_t n, size_t chunk, F &&fn) {
  parallel((n + chunk - 1) / chunk, [&](size_t c) { fn(c * chunk, std::min(n, (c + 1) * chunk)); });
}

}  // namespace nimbus::sdk
