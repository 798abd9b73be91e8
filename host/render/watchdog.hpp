// The watchdog of a render with a time budget. A render stops by time between iterations, so it may run
// one iteration past its budget; a plugin hook still running long after that (a hang, a deadlock, a sleep)
// would keep the render, and its finished iterations, hostage forever. Past the budget plus a grace the
// watchdog calls `rescue` with the hook it found running; the rescue writes what is complete and ends the
// process (the hook's thread cannot be stopped).
#pragma once

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

#include "abi/hook_watch.hpp"

namespace nimbus {

class Watchdog {
 public:
  using Rescue = std::function<void(const HookWatch::Site &site, double seconds_in_hook)>;

  // The grace after the budget: a quarter of it, at least 5 s, so that a legitimately long iteration
  // (a first photon pass, a slow machine) is never taken for a hang.
  static double grace_seconds(double budget) { return budget * 0.25 > 5.0 ? budget * 0.25 : 5.0; }

  // Watches `hooks` from now on when budget_seconds > 0; does nothing otherwise.
  Watchdog(const HookWatch &hooks, double budget_seconds, Rescue rescue);
  ~Watchdog();
  Watchdog(const Watchdog &) = delete;
  Watchdog &operator=(const Watchdog &) = delete;

 private:
  void run(double budget_seconds);

  const HookWatch &hooks_;
  Rescue rescue_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace nimbus
