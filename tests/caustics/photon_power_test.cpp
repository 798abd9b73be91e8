// Solver spec 10 (v), photon power: a point light above a lossless glass slab (two 40 x 40 faces 0.1
// apart) over a diffuse plane. Photons are stored where they land on the plane after the slab, so the
// flux a pass's stored photons carry (statistic caustics_photon_flux, with its standard error over the
// passes) must equal the light's flux into the slab times the slab's transmittance: Fresnel at both faces
// with every internal reflection, T = (1 - R) / (1 + R) for the unpolarised R the dielectric uses, which
// is the same inside and out. The plane reflects a little (albedo 0.05, so that lookups find light and
// Metropolis guiding has a target); light it sends back that the slab's underside returns is stored again,
// a geometric series in albedo x the slab's hemispherical reflectance. Uniform emission and Metropolis
// guiding (photon_emission: guided) must both carry the same flux.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "caustics/reference_light_tracer.hpp"
#include "sphere_scenes.hpp"
#include "support/render_support.hpp"

namespace nimbus::testing {
namespace photon_power_test {

constexpr double kIntensity = 10, kHeight = 1, kHalf = 20, kIor = 1.5, kAlbedo = 0.05;
// Passes estimate the flux independently, so 4 standard errors of their mean bound a correct solver's
// error with probability ~1e-4 (t with ~20 degrees of freedom: ~1e-3).
constexpr double kSigmas = 4;

const std::string kSlab = R"(
render: { resolution: [160, 90], max_depth: 64 }
camera: { position: [0.4, -0.6, 3], look_at: [0, 0, -0.6], up: [0, 1, 0], fov: 60 }
materials:
  glass: { type: dielectric, ior: 1.5 }
  floor: { type: diffuse, albedo: [0.05, 0.05, 0.05] }
objects:
  - { shape: rectangle, size: [40, 40], material: glass }
  - { shape: rectangle, size: [40, 40], material: glass, transform: { rotate: [180, 0, 0], translate: [0, 0, -0.1] } }
  - { shape: rectangle, size: [200, 200], material: floor, transform: { translate: [0, 0, -0.6] } }
lights:
  - { type: point, position: [0, 0, 1], intensity: [10, 10, 10] }
)";

// The slab's transmittance at incidence cosine mu.
double slab_transmittance(double mu) {
  double cos_t = 0;
  const double r = reference::fresnel(mu, 1 / kIor, cos_t);
  return (1 - r) / (1 + r);
}

// Integral of f over [a, b] by Simpson's rule on n (even) intervals.
template <class F>
double simpson(F f, double a, double b, int n = 2000) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += f(a + i * h) * (i % 2 ? 4 : 2);
  return s * h / 3;
}

// The flux stored on the plane: I times the integral of T over the solid angle of the slab's top (polar
// angle phi, mu = cos of the angle from the normal; by symmetry 8 times the wedge 0 <= phi <= 45 degrees,
// where the square's edge is at distance kHalf / cos phi), over 1 - albedo x the slab's cosine-weighted
// reflectance 1 - T seen from below.
double expected_flux() {
  const double through = 8 * simpson(
                                 [](double phi) {
                                   const double rho = kHalf / std::cos(phi);
                                   const double mu_min = kHeight / std::hypot(kHeight, rho);
                                   return simpson(slab_transmittance, mu_min, 1.0, 400);
                                 },
                                 0.0, M_PI / 4, 200);
  const double reflectance = simpson([](double mu) { return (1 - slab_transmittance(mu)) * 2 * mu; }, 0, 1);
  return kIntensity * through / (1 - kAlbedo * reflectance);
}

// guided_share: the least share of the passes whose paths the guide's chains chose.
void stores_the_transmitted_flux(const std::vector<std::pair<std::string, std::string>> &options,
                                 double guided_share) {
  SceneRenderer r;
  RenderRequest q = request("nimbus.caustics", 48, 7);
  q.options = options;
  const ImageLayers img = r.render(kSlab, q);
  const double want = expected_flux(), flux = stat(img, "caustics_photon_flux");
  const double se = stat(img, "caustics_photon_flux_se"), passes = stat(img, "caustics_photon_passes");
  std::printf("stored flux %.5f (SE %.5f over %.0f passes, %.0f guided), analytic %.5f: ratio %.5f\n", flux,
              se, passes, stat(img, "caustics_guided_passes"), want, flux / want);
  EXPECT_GE(passes, 8.0);
  EXPECT_GT(se, 0.0);
  EXPECT_LT(kSigmas * se, 0.01 * want) << "too few photons to see a 1 % error";
  EXPECT_NEAR(flux, want, kSigmas * se);
  EXPECT_GE(stat(img, "caustics_guided_passes"), guided_share * passes);
}

TEST(CausticsPhotonPower, StoredFluxIsTheSlabsTransmittance) { stores_the_transmitted_flux({}, 0); }

TEST(CausticsPhotonPower, GuidedStoredFluxIsTheSlabsTransmittance) {
  // Every pass after the first lookups marked the plane (the probe and the next are uniform).
  stores_the_transmitted_flux({{"photon_emission", "guided"}}, 0.75);
}

}  // namespace photon_power_test
}  // namespace nimbus::testing
