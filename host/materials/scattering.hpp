// The vocabulary every BSDF shares: transport mode, the sample record, and (through the headers below)
// local-frame trigonometry, reflect/refract, Fresnel and the GGX microfacet distribution.
#pragma once

#include <nimbus/bsdf.h>

#include <cstdint>

#include <nimbus/cpp/math.hpp>
#include "materials/fresnel.hpp"
#include "materials/local_frame.hpp"
#include "materials/microfacet.hpp"

namespace nimbus {

// Radiance: wo leads towards the camera. Importance: wo leads towards a light (photons, light paths); the
// BSDF is then the adjoint, which for refraction drops the 1/eta^2 radiance compression.
enum class TransportMode { Radiance, Importance };

struct BsdfSample {
  Vec3f wi;
  Rgb f;              // BSDF value without the cosine; for a delta lobe, weight / |cos wi|
  float pdf = 0;      // solid-angle pdf of wi; 1 for a delta lobe; 0 = no sample
  float pdf_rev = 0;  // pdf of sampling wo given wi; 1 for a delta lobe
  float eta = 1;      // relative IOR crossed (1 unless a refraction was sampled)
  uint32_t lobe = 0;  // the single lobe sampled: NIMBUS_LOBE_* bits, e.g. REFLECTION | GLOSSY
};

// Every sample() ends here: a sample whose numbers went non-finite (grazing angles, extreme IORs) becomes
// "no sample" rather than poisoning the film.
inline BsdfSample checked_sample(const BsdfSample &s) {
  const bool ok = s.pdf > 0 && std::isfinite(s.pdf) && std::isfinite(s.pdf_rev) && s.pdf_rev >= 0 &&
                  is_finite(s.f) && is_finite(s.wi);
  return ok ? s : BsdfSample{};
}

}  // namespace nimbus
