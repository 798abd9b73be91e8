/* Nimbus SDK: deterministic random numbers (nimbus.host.rng@1).
 *
 * Streams derive from (scene seed, key, iteration, dimension), never from the thread, so a fixed seed
 * gives the same image at any thread count. The generator is PCG32 (O'Neill 2014, XSH-RR), inline
 * here so that drawing a number costs no call; its definition is frozen for the whole major. */
#ifndef NIMBUS_RNG_H
#define NIMBUS_RNG_H

#include "host.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct nimbus_rng {
  uint64_t state, inc;
} nimbus_rng_t;

#define NIMBUS_SERVICE_RNG "nimbus.host.rng"
typedef struct nimbus_host_rng_v1 {
  uint32_t struct_size;
  /* [any-thread] Seeds *out (out) for `key` (a pixel index, a photon path index...), `iteration`
   * and `stream` (a dimension or purpose, so that independent uses never share numbers). */
  void (*derive)(const nimbus_host_t *host, uint64_t key, uint64_t iteration, uint64_t stream,
                 nimbus_rng_t *out);
} nimbus_host_rng_v1_t;

static inline uint32_t nimbus_rng_next_u32(nimbus_rng_t *rng) {
  uint64_t old = rng->state;
  rng->state = old * 6364136223846793005ULL + rng->inc;
  uint32_t xorshifted = (uint32_t)(((old >> 18u) ^ old) >> 27u);
  uint32_t rot = (uint32_t)(old >> 59u);
  return (xorshifted >> rot) | (xorshifted << ((-rot) & 31u));
}

/* Uniform float in [0, 1): 24 random mantissa bits, so 1 - 2^-24 is the largest value. */
static inline float nimbus_rng_next_float(nimbus_rng_t *rng) {
  return (float)(nimbus_rng_next_u32(rng) >> 8) * (1.0f / 16777216.0f);
}

#ifdef __cplusplus
}
#endif

#endif /* NIMBUS_RNG_H */
