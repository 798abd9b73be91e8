// Spot lights: a point light whose intensity falls off smoothly towards the edge of a cone.
#include <nimbus/cpp/sampling.hpp>
#include "lights/light.hpp"

namespace nimbus {

float SpotLight::falloff(float cos_theta) const {
  if (cos_theta >= cos_falloff_start) return 1;
  if (cos_theta <= cos_falloff_end) return 0;
  const float t = (cos_theta - cos_falloff_end) / (cos_falloff_start - cos_falloff_end);
  return t * t * (3 - 2 * t);  // smoothstep, as pbrt-v4
}

}  // namespace nimbus
