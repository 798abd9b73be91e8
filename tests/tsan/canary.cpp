// A race ThreadSanitizer must report (tests/tsan/run.sh): two tasks of one tbb::parallel_for write the
// same variable. If the suppressions ever hid a race in our code between TBB tasks, or TBB were not the
// instrumented build, this would stop being reported and the run would fail.
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>

int main() {
  long shared = 0;
  // Relaxed: waiting for the second thread must not order the two tasks' writes.
  std::atomic<int> entered{0};
  const auto task = [&](int i) {
    entered.fetch_add(1, std::memory_order_relaxed);
    // Both tasks run at once on two threads (or give up after 10 s: then nothing is reported and the
    // run fails, as it should when it cannot show that it finds races).
    const auto t0 = std::chrono::steady_clock::now();
    while (entered.load(std::memory_order_relaxed) < 2 &&
           std::chrono::steady_clock::now() - t0 < std::chrono::seconds(10))
      std::this_thread::yield();
    shared += i + 1;  // the race
  };
  tbb::task_arena arena(2);
  arena.execute([&] { tbb::parallel_for(0, 2, task); });
  std::printf("shared = %ld\n", shared);
  return 0;
}
