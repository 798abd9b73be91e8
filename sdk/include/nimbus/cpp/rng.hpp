// Random numbers for plugin code: the draw from a host-derived stream, and the splitmix64 finaliser for
// hashing keys into streams or tables. The generator itself is nimbus/rng.h's. Requires C++17.
#pragma once

#include <cstdint>
#include <initializer_list>

#include <nimbus/rng.h>

namespace nimbus {

// The next uniform float in [0, 1) of stream r.
inline float next_uniform(nimbus_rng_t &r) { return nimbus_rng_next_float(&r); }

constexpr uint64_t mix64(uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

constexpr uint64_t hash_keys(std::initializer_list<uint64_t> keys) {
  uint64_t h = 0x6a09e667f3bcc909ULL;
  for (uint64_t k : keys) h = mix64(h ^ mix64(k));
  return h;
}

}  // namespace nimbus
