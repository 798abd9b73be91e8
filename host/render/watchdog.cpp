#include "render/watchdog.hpp"

namespace nimbus {

Watchdog::Watchdog(const HookWatch &hooks, double budget_seconds, Rescue rescue)
    : hooks_(hooks), rescue_(std::move(rescue)) {
  if (budget_seconds > 0) thread_ = std::thread([this, budget_seconds] { run(budget_seconds); });
}

Watchdog::~Watchdog() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void Watchdog::run(double budget_seconds) {
  using Clock = HookWatch::Clock;
  const auto start = Clock::now();
  const auto deadline = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
                                    budget_seconds + grace_seconds(budget_seconds)));
  std::unique_lock lock(mutex_);
  while (!wake_.wait_for(lock, std::chrono::milliseconds(100), [&] { return stop_; })) {
    if (Clock::now() < deadline) continue;
    const HookWatch::Site site = hooks_.now();
    if (site.hook.empty()) continue;
    lock.unlock();
    rescue_(site, std::chrono::duration<double>(Clock::now() - site.since).count());
    return;
  }
}

}  // namespace nimbus
