// Flush-to-zero and denormals-are-zero (the FTZ and DAZ bits of x86's MXCSR) for every thread that
// renders. Embree asks for both before its ray queries: arithmetic that meets a denormal takes a
// microcode assist of about a hundred cycles, and axis-aligned geometry makes such values common in
// traversal and in shading alike (docs/performance.md §1). Every render thread runs in the same mode, so
// images stay the same at any thread count. Values below 2^-126 become zero, far below anything a pixel
// can show.
#pragma once

#include <tbb/task_arena.h>
#include <tbb/task_scheduler_observer.h>

#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#endif

namespace nimbus {

#if defined(__SSE__) || defined(__x86_64__)
inline constexpr unsigned kFlushDenormals = 0x8040u;  // FTZ (bit 15) | DAZ (bit 6)
inline unsigned read_float_mode() { return _mm_getcsr(); }
inline void write_float_mode(unsigned mode) { _mm_setcsr(mode); }
#else
inline constexpr unsigned kFlushDenormals = 0;
inline unsigned read_float_mode() { return 0; }
inline void write_float_mode(unsigned) {}
#endif

// The calling thread flushes denormals while this lives, then gets its previous mode back.
class FlushDenormals {
 public:
  FlushDenormals() : saved_(read_float_mode()) { write_float_mode(saved_ | kFlushDenormals); }
  ~FlushDenormals() { write_float_mode(saved_); }
  FlushDenormals(const FlushDenormals &) = delete;
  FlushDenormals &operator=(const FlushDenormals &) = delete;

 private:
  unsigned saved_;
};

// Every thread that joins `arena` flushes denormals while it works there (workers and callers of
// execute alike); a thread that leaves gets its previous mode back.
class ArenaFlushDenormals : public tbb::task_scheduler_observer {
 public:
  explicit ArenaFlushDenormals(tbb::task_arena &arena) : tbb::task_scheduler_observer(arena) {
    observe(true);
  }
  ~ArenaFlushDenormals() override { observe(false); }

  void on_scheduler_entry(bool) override {
    if (depth()++ == 0) saved() = read_float_mode();
    write_float_mode(read_float_mode() | kFlushDenormals);
  }
  void on_scheduler_exit(bool) override {
    if (--depth() == 0) write_float_mode(saved());
  }

 private:
  static unsigned &saved() {
    thread_local unsigned mode = 0;
    return mode;
  }
  static int &depth() {
    thread_local int n = 0;
    return n;
  }
};

}  // namespace nimbus
