// How the photon map's builders run loops in parallel: the plugin passes the host's task service, tests a
// plain loop or threads of their own.
#pragma once

#include <cstddef>
#include <functional>

namespace nimbus::caustics {

// Runs fn(i) for i in [0, count), possibly concurrently.
using ParallelFor = std::function<void(size_t count, const std::function<void(size_t)> &fn)>;

inline void serial_for(size_t count, const std::function<void(size_t)> &fn) {
  for (size_t i = 0; i < count; ++i) fn(i);
}

}  // namespace nimbus::caustics
