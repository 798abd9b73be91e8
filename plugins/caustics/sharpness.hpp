// Vertex classification (solver spec section 2): a vertex is sharp (caustic-forming) when every lobe of
// its material is delta or GGX with alpha below kSharpAlpha, rough otherwise. Decided by the material,
// not by the lobe a path happened to sample, so camera and photon paths classify a vertex alike.
#pragma once

#include <nimbus/bsdf.h>
#include <nimbus/host.h>

#include "mis.hpp"

namespace nimbus::caustics {

inline bool has(nimbus_lobe_t lobes, nimbus_lobe_t bits) { return (lobes & bits) != 0; }

inline bool is_sharp(const nimbus_host_bsdf_v1_t *bsdf, const nimbus_host_t *h,
                     const nimbus_interaction_t &ix, nimbus_lobe_t lobes) {
  if (has(lobes, NIMBUS_LOBE_DIFFUSE)) return false;
  if (!has(lobes, NIMBUS_LOBE_GLOSSY)) return has(lobes, NIMBUS_LOBE_SPECULAR);
  return bsdf->min_roughness(h, &ix) < kSharpAlpha;
}

}  // namespace nimbus::caustics
