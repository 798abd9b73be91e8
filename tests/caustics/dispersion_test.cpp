// Dispersion in the caustics solver (spec 7.2): photons past a dispersive glass carry a wavelength and
// their value at it; a lookup weighs a photon by the camera path's colour state (an RGB camera path by
// the photon wavelength's colour weight, a camera path of one wavelength by the photon's uplifted
// colour, or, both of one wavelength, within a window of similar wavelengths). A dispersive glass ball
// under an area light, seen directly and through itself: the solver agrees with nimbus.pt, which
// converges there. (tests/transport/dispersion_test.cpp checks its rainbow against Snell's law.)
#include <gtest/gtest.h>

#include "sphere_scenes.hpp"

namespace nimbus::testing {
namespace dispersion_test {

TEST(CausticsDispersion, DispersiveBallAgreesWithPathTracer) {
  std::string scene = sphere_scene(R"(
  - { shape: rectangle, size: [0.35, 0.35], material: lamp, emission: { radiance: [110, 110, 110] },
      transform: { rotate: [180, 0, 0], translate: [-1.4, 0, 1.9] } }
)");
  const std::string glass = "glass: { type: dielectric, ior: 1.5 }";
  scene.replace(scene.find(glass), glass.size(), "glass: { type: dielectric, ior: 1.6, abbe: 20 }");
  agrees_with_path_tracer(scene);
}

}  // namespace dispersion_test
}  // namespace nimbus::testing
