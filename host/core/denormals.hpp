// Flush-to-zero and denormals-are-zero (the FTZ and DAZ bits of x86's MXCSR) for every thread that
// renders: the main thread for the whole render, and every task the host runs in its arena (render tiles,
// the tasks service's chunks) for the task's duration. Embree asks for both before its ray queries:
// arithmetic that meets a denormal takes a microcode assist of about a hundred cycles, and axis-aligned
// geometry makes such values common in traversal and in shading alike (docs/performance.md §1). Every render
// thread runs in the same mode, so images stay the same at any thread count. Values below 2^-126 become zero,
// far below anything a pixel can show.
#pragma once

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

}  // namespace nimbus
