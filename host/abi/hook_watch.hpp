// Which plugin hook the render is in, and since when: what the watchdog reads to tell a slow render from
// a plugin that has stopped returning, and what its message names.
#pragma once

#include <atomic>
#include <chrono>
#include <mutex>
#include <string>
#include <thread>

namespace nimbus {

class HookWatch {
 public:
  using Clock = std::chrono::steady_clock;
  struct Site {
    std::string plugin, hook;  // empty between hooks
    Clock::time_point since;
  };

  // [main-thread] Around each call into a plugin that the render waits for.
  void enter(const std::string &plugin, const char *hook) {
    std::lock_guard lock(mutex_);
    site_ = {plugin, hook, Clock::now()};
  }
  // A hook that returns while the watchdog rescues the render parks its thread: the rescue owns the film
  // and ends the process.
  void leave() {
    {
      std::lock_guard lock(mutex_);
      site_ = {};
    }
    while (rescuing_.load()) std::this_thread::sleep_for(std::chrono::seconds(1));
  }
  Site now() const {
    std::lock_guard lock(mutex_);
    return site_;
  }

  // [any-thread] From now on no tile starts and no hook returns into the render.
  void start_rescue() { rescuing_.store(true); }
  bool rescuing() const { return rescuing_.load(); }

 private:
  mutable std::mutex mutex_;
  Site site_;
  std::atomic<bool> rescuing_{false};
};

// enter() now, leave() at the end of the scope.
class HookScope {
 public:
  HookScope(HookWatch &w, const std::string &plugin, const char *hook) : w_(w) { w_.enter(plugin, hook); }
  ~HookScope() { w_.leave(); }
  HookScope(const HookScope &) = delete;
  HookScope &operator=(const HookScope &) = delete;

 private:
  HookWatch &w_;
};

}  // namespace nimbus
