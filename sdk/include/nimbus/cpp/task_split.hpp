// A frame's iterations shared between processes (nimbus_render_info_t.task_index and task_count, SDK 1.8):
// task K of N renders the frame-wide iterations K + 1 + k N, k = 0, 1, ..., and numbers anything of its own
// (photon passes) the same way, so that the tasks' random numbers never coincide and their schedules
// interleave into the one a whole render follows.
#pragma once

#include <cstddef>
#include <cstdint>

#include "../integrator.h"

namespace nimbus::sdk {

struct TaskSplit {
  uint32_t index = 0;  // K, in [0, count)
  uint32_t count = 1;  // N; a whole render is task 0 of 1

  // The split a render_info describes (a host before 1.8 renders whole frames).
  static TaskSplit of(const nimbus_render_info_t &info) {
    constexpr size_t needed = offsetof(nimbus_render_info_t, task_count) + sizeof(uint32_t);
    if (info.header.struct_size < needed || info.task_count == 0 || info.task_index >= info.task_count)
      return {};
    return {info.task_index, info.task_count};
  }

  // The frame-wide number of this task's n-th (1-based) iteration or pass (0, none yet, stays 0), and back.
  uint64_t frame_number(uint64_t n) const { return n ? index + 1 + (n - 1) * uint64_t(count) : 0; }
  uint64_t task_number(uint64_t frame) const { return (frame - 1 - index) / count + 1; }
  // How many of the frame's first `frame_total` numbers are this task's.
  uint64_t share_of(uint64_t frame_total) const {
    return frame_total > index ? (frame_total - index - 1) / count + 1 : 0;
  }
  bool whole() const { return count == 1; }
};

}  // namespace nimbus::sdk
