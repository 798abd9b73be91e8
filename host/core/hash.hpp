// Hashing for deterministic random streams: splitmix64 finaliser and combination of several keys.
#pragma once

#include <cstdint>
#include <initializer_list>

#include <nimbus/rng.h>

namespace nimbus {

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

// PCG32 seeding as in the reference implementation (pcg32_srandom_r): stream selects the increment.
inline nimbus_rng_t make_rng(uint64_t seed_state, uint64_t stream) {
  nimbus_rng_t r{0, (stream << 1u) | 1u};
  nimbus_rng_next_u32(&r);
  r.state += seed_state;
  nimbus_rng_next_u32(&r);
  return r;
}

// The stream for (scene seed, key, iteration, purpose): the same on any thread and at any thread count.
inline nimbus_rng_t derive_rng(uint64_t seed, uint64_t key, uint64_t iteration, uint64_t purpose) {
  const uint64_t h = hash_keys({seed, key, iteration, purpose});
  return make_rng(h, mix64(h ^ 0x5851f42d4c957f2dULL));
}

}  // namespace nimbus
