#include "cli/progress_display.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace nimbus::cli {
namespace {

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--:--";
  const long s = std::lround(seconds);
  char buf[32];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
  return buf;
}

// Fraction done: by iterations, or by time when only a budget bounds the render.
double fraction(const RenderProgress &p) {
  double f = 0;
  if (p.total_iterations) f = double(p.iteration) / double(p.total_iterations);
  if (p.time_budget > 0) f = std::max(f, p.elapsed_seconds / p.time_budget);
  return std::clamp(f, 0.0, 1.0);
}

}  // namespace

void ProgressDisplay::update(const RenderProgress &p) {
  if (quiet_) return;
  const double f = fraction(p);
  const double eta = f > 0 ? p.elapsed_seconds * (1 - f) / f : NAN;
  std::string its = std::to_string(p.iteration);
  if (p.total_iterations) its += "/" + std::to_string(p.total_iterations);
  char rate[32];
  std::snprintf(rate, sizeof rate, "%.2f Msamples/s", p.samples_per_second * 1e-6);
  if (tty_) {
    constexpr int kWidth = 30;
    const int filled = int(f * kWidth);
    std::string bar(filled, '#');
    bar.resize(kWidth, '-');
    std::fprintf(out_, "\r[%s] %3d%%  it %s  %s  ETA %s  %s\033[K", bar.c_str(), int(f * 100), its.c_str(),
                 rate, format_duration(eta).c_str(), p.phase.c_str());
    std::fflush(out_);
    drawn_ = true;
    return;
  }
  const auto now = std::chrono::steady_clock::now();
  const bool last = p.total_iterations && p.iteration >= p.total_iterations;
  if (!last && drawn_ && now - last_line_ < std::chrono::seconds(5)) return;
  last_line_ = now;
  drawn_ = true;
  std::fprintf(out_, "nimbus: %3d%%  iteration %s  %s  elapsed %s  ETA %s\n", int(f * 100), its.c_str(), rate,
               format_duration(p.elapsed_seconds).c_str(), format_duration(eta).c_str());
  std::fflush(out_);
}

void ProgressDisplay::finish() {
  if (tty_ && drawn_ && !quiet_) std::fputc('\n', out_);
  drawn_ = false;
}

}  // namespace nimbus::cli
