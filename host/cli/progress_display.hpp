// Progress of a render on the terminal: a bar redrawn in place on a TTY (percent, iterations, samples/s,
// ETA), plain lines every few seconds otherwise (logs, CI).
#pragma once

#include <chrono>
#include <cstdio>

#include "render/render_session.hpp"

namespace nimbus::cli {

class ProgressDisplay {
 public:
  ProgressDisplay(std::FILE *out, bool tty, bool quiet) : out_(out), tty_(tty), quiet_(quiet) {}
  void update(const RenderProgress &p);
  // Ends the bar's line (TTY) so later messages start on a fresh line.
  void finish();

 private:
  std::FILE *out_;
  bool tty_, quiet_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_line_{};
};

}  // namespace nimbus::cli
