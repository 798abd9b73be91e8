// Stand-ins for the host's lights service and two scenes' targets, shared by the projection-map tests
// (emitters_test.cpp) and the photon-power tests (photon_share_test.cpp).
#pragma once

#include <cmath>
#include <vector>

#include "emitters.hpp"

namespace nimbus::caustics::stubs {

// The host's emission densities for the lights of these tests (the lights service's pdf_emission, whose
// own agreement with sample_emission tests/lights checks), by light index: a point light, a spot of
// half angle 0.5 rad along (-1, 0, -1), and a one-sided area light of area 1/4.
inline float pdf_dir_of(uint32_t light, const Vec3f &n, const Vec3f &w) {
  switch (light) {
    case 0:
      return kUniformSpherePdf;
    case 1:
      return dot(w, normalize(Vec3f(-1, 0, -1))) >= std::cos(0.5f) ? uniform_cone_pdf(std::cos(0.5f)) : 0.0f;
    default:
      return cosine_hemisphere_pdf(dot(n, w));
  }
}
inline const nimbus_host_lights_v1_t kStubLights = [] {
  nimbus_host_lights_v1_t t{};
  t.struct_size = sizeof(t);
  t.pdf_emission = [](const nimbus_host_t *, uint32_t light, const float *, const float n[3],
                      const float dir[3], float *pdf_pos, float *pdf_dir) {
    *pdf_pos = light == 2 ? 4.0f : 1.0f;
    *pdf_dir = pdf_dir_of(light, Vec3f::load(n), Vec3f::load(dir));
  };
  return t;
}();

// Two targets: a ball in front of the lights and a smaller one off to the side.
inline SharpTargets two_targets() {
  std::vector<Target> objects = {{{Vec3f(0, 0, 0.5f), 0.5f}, Vec3f(-0.5f, -0.5f, 0), Vec3f(0.5f, 0.5f, 1)},
                                 {{Vec3f(3, 1, 0.2f), 0.2f}, Vec3f(2.8f, 0.8f, 0), Vec3f(3.2f, 1.2f, 0.4f)}};
  SharpTargets t;
  cluster(objects, kMaxTargets, t.clusters);
  t.all = enclose(t.clusters);
  return t;
}

inline std::vector<Emitter> three_lights() {
  std::vector<Emitter> lights(3);
  lights[0].kind = EmitterKind::Point, lights[0].power = 2, lights[0].position = Vec3f(-2, 0, 2);
  lights[0].flags = NIMBUS_LIGHT_DELTA_POSITION;
  lights[1].kind = EmitterKind::Spot, lights[1].power = 1, lights[1].position = Vec3f(2, 0, 2);
  lights[1].flags = NIMBUS_LIGHT_DELTA_POSITION;
  lights[1].axis = normalize(Vec3f(-1, 0, -1)), lights[1].cos_theta_e = std::cos(0.5f);
  lights[2].kind = EmitterKind::Area, lights[2].power = 1, lights[2].position = Vec3f(0.1f, 0.05f, 3);
  lights[2].flags = NIMBUS_LIGHT_AREA;
  return lights;
}

}  // namespace nimbus::caustics::stubs
