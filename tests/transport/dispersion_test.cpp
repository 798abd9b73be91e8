// Dispersion in nimbus.pt and nimbus.lt (SDK 1.7): paths become one wavelength at a dispersive glass.
// A prism under an area light: the two renders, which share only the host's materials, lights and
// camera, agree (their difference falls as their noise does, their means match per channel). A prism in a
// horizontal delta sun throws its rainbow on the floor: the light tracer's colours land in the order and
// at the spread Snell's law gives with the glass's index curve, traced in 2D in the test itself. A scene
// without dispersive glass draws no wavelength: its image is the RGB one, bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <nimbus/cpp/spectral.hpp>

#include "support/render_support.hpp"

namespace nimbus::testing {
namespace dispersion_test {

RenderRequest request(const std::string &integrator, uint64_t iterations, uint64_t seed) {
  RenderRequest req;
  req.integrator = integrator, req.iterations = iterations, req.seed = seed;
  return req;
}

// Dense flint: n_d = 1.75, Abbe number 25 (a two-term Cauchy curve through n_d with that dispersion).
constexpr double kNd = 1.75, kVd = 25;
double flint_index(double lambda_nm) {
  // n = A + B / lambda^2 with n(587.56) = n_d and n(486.13) - n(656.27) = (n_d - 1) / V_d.
  const double f = 0.48613, c = 0.65627, d = 0.58756;  // micrometres
  const double b = (kNd - 1) / kVd / (1 / (f * f) - 1 / (c * c)), a = kNd - b / (d * d);
  const double l = lambda_nm / 1000;
  return a + b / (l * l);
}

const std::string kPrism = "shape: mesh, file: " + std::string(NIMBUS_SOURCE_DIR) +
                           "/scenes/caustics/assets/prism.obj, material: flint";

// The prism: side 0.2, apex up, its base at height kBase, its axis along y (2 long). A narrow spot
// (uniform within kCone degrees) at kSpot shines up at it along 31 degrees, the entry angle of minimum
// deviation for n = 1.75, so the beam leaves the far face heading down to the floor at about x = 1.5.
constexpr double kSide = 0.2, kBase = 0.8, kCone = 2.5, kElevation = 31;
constexpr double kSpot[2] = {-0.907, 0.371};  // (x, z)
const std::string kPrismObject =
    "  - { " + kPrism + ", transform: { scale: [0.2, 2, 0.2], translate: [0, 0, 0.8] } }\n";

// The floor seen from 2.5 m above around x = 1.5 (the camera never sees the glass, so the light tracer,
// which leaves glass seen directly black, renders every pixel).
std::string prism_scene(uint32_t w, uint32_t h, const std::string &light) {
  return "render: { resolution: [" + std::to_string(w) + ", " + std::to_string(h) +
         "], max_depth: 8 }\n"
         "camera: { position: [1.5, 0, 2.5], look_at: [1.5, 0, 0], up: [0, 1, 0], fov: 25 }\n"
         "materials:\n  floor: { type: diffuse, albedo: 1 }\n  flint: { type: dielectric, ior: 1.75, abbe: "
         "25 }\n"
         "  lamp: { type: diffuse, albedo: 0 }\n"
         "objects:\n  - { shape: rectangle, size: [8, 8], material: floor }\n" +
         kPrismObject + light;
}

// Under an area light where the spot stands (path tracing converges there too), each channel's image
// mean agrees between the two within 4 standard errors, measured from six seeds of each (the caustic
// through the prism makes both noisy: a few per cent per render).
TEST(Dispersion, PathTracerAgreesWithLightTracerOnAPrism) {
  const std::string scene =
      prism_scene(32, 24,
                  "  - { shape: rectangle, size: [0.5, 0.5], material: lamp, emission: { radiance: 25 },\n"
                  "      transform: { rotate: [0, 59, 0], translate: [-0.907, 0, 0.371] } }\n");
  SceneRenderer r;
  constexpr int kSeeds = 6;
  std::vector<double> means[2][3];
  for (int i = 0; i < 2; ++i)
    for (int k = 0; k < kSeeds; ++k) {
      const auto img = r.render(scene, request(i == 0 ? "nimbus.pt" : "nimbus.lt", 1024, 20 + uint64_t(k)));
      const Rgb m = mean_rgb(img.layers.at("beauty").data);
      for (int c = 0; c < 3; ++c) means[i][c].push_back(m[c]);
    }
  for (int c = 0; c < 3; ++c) {
    const auto [pt, se_pt] = mean_and_se(means[0][c]);
    const auto [lt, se_lt] = mean_and_se(means[1][c]);
    std::printf("channel %d: pt %.5f +- %.5f, lt %.5f +- %.5f\n", c, pt, se_pt, lt, se_lt);
    EXPECT_NEAR(pt, lt, 4 * std::hypot(se_pt, se_lt)) << "channel " << c;
  }
}

// Snell's law in the prism's cross-section, traced in the test: where a ray leaving the spot at
// kElevation + theta degrees lands on the floor, and the share of light the two refractions transmit
// (unpolarised Fresnel); share 0 where it does not reach the floor through the far face.
struct Landing {
  double x = 0, share = 0;
};
double fresnel_transmittance(double cos_i, double eta) {  // eta = n_t / n_i
  const double sin_t2 = (1 - cos_i * cos_i) / (eta * eta);
  if (sin_t2 >= 1) return 0;
  const double cos_t = std::sqrt(1 - sin_t2);
  const double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t),
               rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 1 - 0.5 * (rs * rs + rp * rp);
}
// Refracts (dx, dz) through a face whose unit normal (nx, nz) points against it, at eta = n_t / n_i.
bool refract(double &dx, double &dz, double nx, double nz, double eta, double &share) {
  const double cos_i = -(dx * nx + dz * nz);
  const double sin_t2 = (1 - cos_i * cos_i) / (eta * eta);
  if (sin_t2 >= 1) return false;
  const double cos_t = std::sqrt(1 - sin_t2);
  dx = dx / eta + (cos_i / eta - cos_t) * nx, dz = dz / eta + (cos_i / eta - cos_t) * nz;
  share *= fresnel_transmittance(cos_i, eta);
  return true;
}
Landing land(double theta_deg, double n) {
  const double a = (kElevation + theta_deg) * M_PI / 180, c30 = std::sqrt(3.0) / 2, s30 = 0.5;
  const double h = kSide * c30, offset = c30 * kSide / 2;  // faces: +-c30 x + s30 (z - base) = offset
  double dx = std::cos(a), dz = std::sin(a), share = 1;
  const double t1 = (offset - (-c30 * kSpot[0] + s30 * (kSpot[1] - kBase))) / (-c30 * dx + s30 * dz);
  const double qx = kSpot[0] + t1 * dx, qz = kSpot[1] + t1 * dz;
  if (!(qz >= kBase && qz <= kBase + h) || !refract(dx, dz, -c30, s30, n, share)) return {};
  const double t2 = (offset - (c30 * qx + s30 * (qz - kBase))) / (c30 * dx + s30 * dz);
  const double ex = qx + t2 * dx, ez = qz + t2 * dz;
  if (!(t2 > 0 && ez >= kBase) || !refract(dx, dz, -c30, -s30, 1 / n, share) || !(dz < 0)) return {};
  return {ex + dx * (-ez / dz), share};
}

// The spot's rainbow on the floor, rendered by the light tracer (a delta light through glass: only light
// tracing and photons see it): each channel's centroid along x against Snell's law.
TEST(Dispersion, RainbowFollowsSnellsLawWithTheGlasssIndexCurve) {
  constexpr uint32_t kW = 160, kH = 40;
  const std::string scene = prism_scene(
      kW, kH,
      "lights:\n  - { type: spot, position: [-0.907, 0, 0.371], direction: [0.857, 0, 0.515], cone: 2.5, "
      "softness: 0, intensity: 50 }\n");
  // Equal-energy light (the spot's white uplifts flat), uniform over the cone's solid angle: its slice
  // through the prism's cross-section weighs the angle theta by the cone's chord, sqrt(cone^2 - theta^2).
  double expected[3];
  for (int c = 0; c < 3; ++c) {
    double sum = 0, moment = 0;
    for (double lambda = kLambdaMin + 0.5; lambda < kLambdaMax; lambda += 1)
      for (int k = 0; k < 200; ++k) {
        const double theta = kCone * (2 * (k + 0.5) / 200 - 1);
        const Landing l = land(theta, flint_index(lambda));
        const double w =
            l.share * std::sqrt(kCone * kCone - theta * theta) * spectral_rgb_weight(float(lambda))[c];
        sum += w, moment += w * l.x;
      }
    expected[c] = moment / sum;
  }
  // The light tracer, and the caustics solver whose photons disperse as the light tracer's paths do.
  SceneRenderer r;
  const double pixel = 2 * 2.5 * std::tan(12.5 * M_PI / 180) / kW;  // floor metres per column
  for (const char *integrator : {"nimbus.lt", "nimbus.caustics"}) {
    const auto img = r.render(scene, request(integrator, 64, 5));
    const std::vector<float> &d = img.layers.at("beauty").data;
    double measured[3];
    for (int c = 0; c < 3; ++c) {
      double sum = 0, moment = 0;
      for (uint32_t y = 0; y < kH; ++y)
        for (uint32_t x = 0; x < kW; ++x) {
          const double v = d[3 * (size_t(y) * kW + x) + size_t(c)], fx = 1.5 + (x + 0.5 - kW / 2.0) * pixel;
          sum += v, moment += v * fx;
        }
      measured[c] = moment / sum;
    }
    std::printf("%s: channel centroids on the floor (m): R %.4f G %.4f B %.4f; Snell R %.4f G %.4f B %.4f\n",
                integrator, measured[0], measured[1], measured[2], expected[0], expected[1], expected[2]);
    // Hue order: blue bends most, so it lands nearest the prism (smallest x), then green, then red.
    EXPECT_LT(measured[2], measured[1]) << integrator;
    EXPECT_LT(measured[1], measured[0]) << integrator;
    // The spread between red and blue within 10 %, and each centroid within two columns.
    EXPECT_NEAR(measured[0] - measured[2], expected[0] - expected[2], 0.1 * (expected[0] - expected[2]))
        << integrator;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(measured[c], expected[c], 2 * pixel) << integrator << " channel " << c;
  }
}

// No dispersive material: no wavelength is drawn and the RGB image comes out bit for bit.
TEST(Dispersion, ConstantIndexGlassRendersAsBefore) {
  const auto scene = [](const std::string &glass) {
    return "render: { resolution: [24, 16], max_depth: 6 }\n"
           "camera: { position: [0.6, -1.6, 1.2], look_at: [0.1, 0, 0.2], up: [0, 0, 1], fov: 40 }\n"
           "materials:\n  floor: { type: diffuse, albedo: 0.7 }\n  flint: { type: dielectric, " +
           glass +
           " }\n  lamp: { type: diffuse, albedo: 0 }\nobjects:\n  - { shape: rectangle, size: [4, 4], "
           "material: floor }\n"
           "  - { " +
           kPrism +
           ", transform: { scale: 0.4 } }\n"
           "  - { shape: rectangle, size: [0.5, 0.5], material: lamp, emission: { radiance: 20 },\n"
           "      transform: { rotate: [0, 120, 0], translate: [-0.9, 0, 0.6] } }\n";
  };
  SceneRenderer r;
  for (const char *integrator : {"nimbus.pt", "nimbus.lt"}) {
    const auto plain = r.render(scene("ior: 1.75"), request(integrator, 4, 9));
    const auto flat = r.render(scene("cauchy: [1.75, 0]"), request(integrator, 4, 9));
    EXPECT_EQ(plain.layers.at("beauty").data, flat.layers.at("beauty").data) << integrator;
  }
}

}  // namespace dispersion_test
}  // namespace nimbus::testing
