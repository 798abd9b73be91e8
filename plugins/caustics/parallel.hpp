// How the photon map's builders run loops in parallel: the plugin passes the host's task service, tests a
// plain loop or threads of their own.
#pragma once

#include <algorithm>
#include <cstddef>
#include <functional>

namespace nimbus::caustics {

// Runs fn(i) for i in [0, count), possibly concurrently.
using ParallelFor = std::function<void(size_t count, const std::function<void(size_t)> &fn)>;

inline void serial_for(size_t count, const std::function<void(size_t)> &fn) {
  for (size_t i = 0; i < count; ++i) fn(i);
}

// Runs fn(begin, end) over [0, n) in ranges of `chunk`, the ranges possibly concurrently.
template <class F>
void parallel_ranges(const ParallelFor &parallel, size_t n, size_t chunk, F &&fn) {
  parallel((n + chunk - 1) / chunk, [&](size_t c) { fn(c * chunk, std::min(n, (c + 1) * chunk)); });
}

}  // namespace nimbus::caustics
