// Seeding of the deterministic random streams the host derives for plugins (nimbus.host.rng).
#pragma once

#include <cstdint>

#include <nimbus/rng.h>
#include <nimbus/cpp/rng.hpp>

namespace nimbus {

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
