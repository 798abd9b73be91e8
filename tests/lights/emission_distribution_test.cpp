// The densities pdf_emission states are the ones sample_emission draws from: chi-square tests of the
// histogram of sampled directions (every light with a direction density) and of sampled positions (area
// lights) against the counts pdf_emission predicts for each cell, through the lights service's C table.
//
// Tolerances: each test draws its own fixed-seed samples (10^6 directions, 4 x 10^5 mesh positions) and
// passes when (1) the chi-square p-value exceeds the Sidak share of a 1 % false-alarm rate over the
// kTests tests of this file (7.2e-4 each), (2) no cell (pooled sparse ones counting as one) is more than
// 5 standard deviations sqrt(expected) away from its expected count, which a correct sampler exceeds in
// one of ~3000 cells with probability ~2e-3, and (3) the pdf integrates to 1 within 2e-3 where the
// histogram covers the whole domain (adaptive quadrature, chi_square.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "emission_support.hpp"
#include "materials/chi_square.hpp"

namespace nimbus::testing {
namespace emission_distribution_test {

using test::ChiSquareConfig;
using test::ChiSquareResult;
using test::Pcg32;

constexpr int kTests = 14;
constexpr double kMaxSigma = 5;

void expect_fit(const ChiSquareResult &r, const std::string &what, bool whole_domain = true) {
  std::printf("%s: %s\n", what.c_str(), r.describe().c_str());
  EXPECT_TRUE(r.error.empty()) << what << ": " << r.describe();
  EXPECT_GT(r.p_value, test::sidak_significance(0.01, kTests)) << what << ": " << r.describe();
  EXPECT_LE(r.worst_sigma, kMaxSigma) << what << ": " << r.describe();
  if (whole_domain) {
    EXPECT_NEAR(r.pdf_integral, 1.0, 2e-3) << what << ": " << r.describe();
  }
}

nimbus_light_emission_t draw(const LightsHarness &h, uint32_t l, Pcg32 &rng) {
  const float u[4] = {rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform()};
  return h.sample(l, u);
}
bool valid(const nimbus_light_emission_t &es) { return es.pdf_pos > 0 && es.pdf_dir > 0; }

// Directions of light `l` expressed in `frame` (so that a cone around its n spans whole theta bins),
// against pdf_dir at p with normal n.
ChiSquareResult direction_fit(const LightsHarness &h, uint32_t l, const Frame &frame, const Vec3f &p,
                              const Vec3f &n, ChiSquareConfig cfg) {
  return test::chi_square_test(
      [&](Pcg32 &rng) -> std::optional<Vec3f> {
        const nimbus_light_emission_t es = draw(h, l, rng);
        if (!valid(es)) return std::nullopt;
        return frame.to_local(Vec3f::load(es.dir));
      },
      [&](const Vec3f &w) { return double(h.pdf_dir(l, p, n, frame.to_world(w))); }, cfg);
}

TEST(EmissionDistribution, PointLightDirections) {
  const LightsHarness h(kDeltaScene);
  ChiSquareConfig cfg;
  cfg.seed = 1;
  expect_fit(direction_fit(h, 0, Frame::from_normal({0, 0, 1}), {}, {}, cfg), "point");
}

// Cones (the spot's 45 degrees, the sun's 10): a sphere grid would cut through the rim, where float
// directions fall on either side of it. Instead the cap itself in the light's frame, on cells equal in
// solid angle: 20 bands uniform in cos(theta) down to the rim, 36 in phi; expected counts from pdf_dir at
// 3 x 3 points of each cell times its solid angle; photons beyond the rim form one more category, which
// expects the pdf's missing mass (none).
ChiSquareResult cap_fit(const LightsHarness &h, uint32_t l, uint64_t seed) {
  const nimbus_light_info_t info = h.info(l);
  const Frame frame = Frame::from_normal(Vec3f::load(info.axis));
  const double one_minus_cos = 1 - double(info.cos_theta_e), two_pi = 2 * M_PI;
  constexpr int kBands = 20, kPhi = 36, kSamples = 1000000;
  const int cells = kBands * kPhi;
  std::vector<double> observed(cells + 1, 0), expected(cells + 1, 0);
  double total = 0;
  for (int b = 0; b < kBands; ++b)
    for (int f = 0; f < kPhi; ++f) {
      double mean = 0;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const double t = (b + (i + 0.5) / 3) / kBands * one_minus_cos,
                       phi = (f + (j + 0.5) / 3) / kPhi * two_pi;
          const double sin_theta = std::sqrt(t * (2 - t));
          const Vec3f w(float(sin_theta * std::cos(phi)), float(sin_theta * std::sin(phi)), float(1 - t));
          mean += h.pdf_dir(l, {}, {}, frame.to_world(w)) / 9.0;
        }
      const double share = mean * one_minus_cos / kBands * two_pi / kPhi;
      expected[size_t(b * kPhi + f)] = share * kSamples;
      total += share;
    }
  EXPECT_NEAR(total, 1.0, 1e-4) << "light " << l << ": pdf_dir integrates to 1 over the cap";
  expected[cells] = std::max(0.0, 1 - total) * kSamples;
  Pcg32 rng(seed);
  for (int s = 0; s < kSamples; ++s) {
    const nimbus_light_emission_t es = draw(h, l, rng);
    const Vec3f w = frame.to_local(Vec3f::load(es.dir));
    // 1 - cos from sin^2, exact near the axis: 1 - cos = sin^2 / (1 + cos).
    const double sin2 = double(w.x) * w.x + double(w.y) * w.y, t = sin2 / (1 + double(w.z)) / one_minus_cos;
    double phi = std::atan2(double(w.y), double(w.x));
    if (phi < 0) phi += two_pi;
    if (!valid(es) || w.z <= 0 || t >= 1 + 1e-5) {  // beyond rounding of the rim
      observed[cells] += 1;
      continue;
    }
    const int b = std::min(kBands - 1, int(t * kBands)), f = std::min(kPhi - 1, int(phi / two_pi * kPhi));
    observed[size_t(b * kPhi + f)] += 1;
  }
  return test::chi_square_counts(observed, expected, 5);
}

TEST(EmissionDistribution, SpotAndSunDirections) {
  const LightsHarness h(kDeltaScene);
  expect_fit(cap_fit(h, 1, 2), "spot", false);
  expect_fit(cap_fit(h, 2, 3), "sun", false);
}

// Environments on their own lat-long grid (of the direction towards the light, -dir): cells of k x k
// texels of the sampling grid (the 64 x 32 map: k = 1; the baked sky's 256 x 128: k = 4), expected counts
// from pdf_dir at each texel's centre times its solid angle, over which the density is constant. A sphere
// grid would put the map's texel edges on cell edges, where float directions fall on either side and the
// hot spot's 10^4 times larger density leaks into its neighbours' quadrature.
ChiSquareResult latlong_fit(const LightsHarness &h, uint32_t width, uint32_t height, int k, uint64_t seed) {
  const uint32_t cw = width / k, ch = height / k, cells = cw * ch;
  constexpr int kSamples = 1000000;
  const double two_pi = 2 * M_PI;
  std::vector<double> observed(cells + 1, 0), expected(cells + 1, 0);
  double total = 0;
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      // Midpoint rule on pdf x sin(theta) over kRows rows of the texel: exact for a density constant in
      // (u, v) (the map and the sky), 3e-5 off for a uniform one (theta steps of pi / (4 height)).
      constexpr int kRows = 4;
      const double phi = (x + 0.5) / width * two_pi, dtheta = M_PI / height / kRows;
      double share = 0;
      for (int r = 0; r < kRows; ++r) {
        const double theta = (y + (r + 0.5) / kRows) / height * M_PI;
        const Vec3f w(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                      float(std::cos(theta)));
        share += double(h.pdf_dir(0, {}, {}, -w)) * std::sin(theta) * dtheta * two_pi / width;
      }
      expected[(y / k) * cw + x / k] += share * kSamples;
      total += share;
    }
  EXPECT_NEAR(total, 1.0, 1e-4) << "pdf_dir integrates to 1 over the sphere";
  expected[cells] = std::max(0.0, 1 - total) * kSamples;
  Pcg32 rng(seed);
  for (int s = 0; s < kSamples; ++s) {
    const nimbus_light_emission_t es = draw(h, 0, rng);
    if (!valid(es)) {
      observed[cells] += 1;
      continue;
    }
    const Vec3f w = -Vec3f::load(es.dir);
    double phi = std::atan2(double(w.y), double(w.x));
    if (phi < 0) phi += two_pi;
    const double theta = std::atan2(std::hypot(double(w.x), double(w.y)), double(w.z));
    const uint32_t x = std::min(width - 1, uint32_t(phi / two_pi * width));
    const uint32_t y = std::min(height - 1, uint32_t(theta / M_PI * height));
    observed[(y / k) * cw + x / k] += 1;
  }
  return test::chi_square_counts(observed, expected, 5);
}

TEST(EmissionDistribution, EnvironmentDirections) {
  const std::string map = write_environment_map("nimbus_emission_distribution.exr");
  const LightsHarness uniform("environment: { color: [0.5, 0.6, 0.7] }\n");
  expect_fit(latlong_fit(uniform, 64, 32, 1, 4), "uniform environment", false);
  const LightsHarness sky("environment: { type: sky, turbidity: 3, sun_direction: [0.3, 0.2, 1] }\n");
  expect_fit(latlong_fit(sky, 256, 128, 4, 5), "sky", false);
  const LightsHarness photo("environment: { map: " + map + " }\n");
  expect_fit(latlong_fit(photo, 64, 32, 1, 6), "map", false);
  std::filesystem::remove(map);
}

// The normal the emitter's side conventions refer to: the front for one-sided lights (the photon's n),
// the shape's own normal for the two-sided disk (the photon's n is the side it left from).
Vec3f geometric_normal(const ShapeRecord &s, const nimbus_light_emission_t &es) {
  return s.type == ShapeType::Disk ? s.normal : Vec3f::load(es.n);
}

// Area lights: directions in the frame of the geometric normal at each photon's own origin, against
// pdf_dir at one photon's origin and normal (the density relative to the normal is the same at every
// point; that it is each photon's own is EmissionConsistency's check).
TEST(EmissionDistribution, AreaLightDirections) {
  const LightsHarness h(kAreaScene);
  for (uint32_t l = 0; l < h.count(); ++l) {
    const ShapeRecord &s = h.context().geometry->shapes()[l];
    Pcg32 first(99);
    const nimbus_light_emission_t ref = draw(h, l, first);
    ASSERT_TRUE(valid(ref));
    const Vec3f p = Vec3f::load(ref.org), n = geometric_normal(s, ref);
    const Frame frame = Frame::from_normal(n);
    ChiSquareConfig cfg;
    cfg.seed = 10 + l;
    const ChiSquareResult r = test::chi_square_test(
        [&](Pcg32 &rng) -> std::optional<Vec3f> {
          const nimbus_light_emission_t es = draw(h, l, rng);
          if (!valid(es)) return std::nullopt;
          return Frame::from_normal(geometric_normal(s, es)).to_local(Vec3f::load(es.dir));
        },
        [&](const Vec3f &w) { return double(h.pdf_dir(l, p, n, frame.to_world(w))); }, cfg);
    expect_fit(r, "area light " + std::to_string(l) + " directions");
  }
}

// Analytic shapes' positions as directions: a sphere's point by its normal (area density x r^2 is the
// solid-angle density), a disk's point lifted onto the hemisphere above it (x r^2 cos theta).
TEST(EmissionDistribution, SphereAndDiskPositions) {
  const LightsHarness h(kAreaScene);
  for (const uint32_t l : {1u, 2u}) {
    const ShapeRecord &s = h.context().geometry->shapes()[l];
    const bool sphere = s.type == ShapeType::Sphere;
    const Frame frame = Frame::from_normal(sphere ? Vec3f(0, 0, 1) : s.normal);
    const float r2 = sqr(s.radius);
    ChiSquareConfig cfg;
    cfg.seed = 20 + l;
    const ChiSquareResult r = test::chi_square_test(
        [&](Pcg32 &rng) -> std::optional<Vec3f> {
          const nimbus_light_emission_t es = draw(h, l, rng);
          if (!valid(es)) return std::nullopt;
          const Vec3f q = frame.to_local(Vec3f::load(es.org) - s.center) / s.radius;
          if (sphere) return normalize(q);
          return Vec3f(q.x, q.y, safe_sqrt(1 - q.x * q.x - q.y * q.y));
        },
        [&](const Vec3f &w) {
          if (sphere)
            return double(h.pdf_pos(l, s.center + frame.to_world(w) * s.radius, frame.to_world(w))) * r2;
          if (!(w.z > 0)) return 0.0;
          const Vec3f on = s.center + (frame.s * w.x + frame.t * w.y) * s.radius;
          return double(h.pdf_pos(l, on, s.normal)) * r2 * w.z;
        },
        cfg);
    expect_fit(r, sphere ? "sphere positions" : "disk positions");
  }
}

// Triangle meshes (the rectangle: 2 triangles; the box: 12 of three sizes): each triangle cut into
// kSub^2 equal triangles, expected counts from pdf_pos at their centroids times their area.
constexpr int kSub = 4;

// The cell of point p on the mesh (triangle, then its (i, j) upward or downward sub-triangle), or -1.
int mesh_cell(const MeshData &m, const Vec3f &p) {
  for (size_t t = 0; t < m.indices.size() / 3; ++t) {
    const Vec3f &p0 = m.positions[m.indices[3 * t]], &p1 = m.positions[m.indices[3 * t + 1]],
                &p2 = m.positions[m.indices[3 * t + 2]];
    const Vec3f e1 = p1 - p0, e2 = p2 - p0, n = cross(e1, e2), d = p - p0;
    const float n2 = length_squared(n);
    if (std::abs(dot(d, n)) > 1e-5f * std::sqrt(n2)) continue;
    const float b1 = dot(cross(d, e2), n) / n2, b2 = dot(cross(e1, d), n) / n2, b0 = 1 - b1 - b2;
    if (b0 < -1e-5f || b1 < -1e-5f || b2 < -1e-5f) continue;
    const auto grid = [](float b) { return std::clamp(int(b * kSub), 0, kSub - 1); };
    const int i = grid(b1), j = grid(b2), k = grid(b0);
    const bool down = i + j + k <= kSub - 2;
    return int(t) * 2 * kSub * kSub + (down ? kSub * kSub : 0) + i * kSub + j;
  }
  return -1;
}

TEST(EmissionDistribution, MeshPositions) {
  const LightsHarness h(kAreaScene);
  constexpr int kSamples = 400000;
  for (const uint32_t l : {0u, 3u}) {
    const MeshData &m = *h.context().geometry->shapes()[l].mesh;
    const size_t triangles = m.indices.size() / 3, cells = triangles * 2 * kSub * kSub;
    std::vector<double> observed(cells + 1, 0), expected(cells + 1, 0);  // last: on no triangle
    double total = 0;
    for (size_t t = 0; t < triangles; ++t) {
      const Vec3f &p0 = m.positions[m.indices[3 * t]], &p1 = m.positions[m.indices[3 * t + 1]],
                  &p2 = m.positions[m.indices[3 * t + 2]];
      const Vec3f n = cross(p1 - p0, p2 - p0);
      const float sub_area = 0.5f * length(n) / (kSub * kSub);
      for (int i = 0; i < kSub; ++i)
        for (int j = 0; i + j < kSub; ++j)
          for (const bool down : {false, true}) {
            if (down && i + j > kSub - 2) continue;
            // Centroid of the sub-triangle in barycentrics (b1, b2).
            const float c1 = (float(i) + (down ? 2.0f : 1.0f) / 3) / kSub;
            const float c2 = (float(j) + (down ? 2.0f : 1.0f) / 3) / kSub;
            const Vec3f c = p0 + (p1 - p0) * c1 + (p2 - p0) * c2;
            const double share = double(h.pdf_pos(l, c, normalize(n))) * sub_area;
            expected[t * 2 * kSub * kSub + (down ? kSub * kSub : 0) + size_t(i) * kSub + size_t(j)] =
                share * kSamples;
            total += share;
          }
    }
    EXPECT_NEAR(total, 1.0, 1e-4) << "light " << l << ": pdf_pos integrates to 1 over the mesh";
    Pcg32 rng(30 + l);
    for (int s = 0; s < kSamples; ++s) {
      const nimbus_light_emission_t es = draw(h, l, rng);
      const int c = valid(es) ? mesh_cell(m, Vec3f::load(es.org)) : -1;
      observed[c < 0 ? cells : size_t(c)] += 1;
    }
    expected[cells] = std::max(0.0, 1 - total) * kSamples;
    expect_fit(test::chi_square_counts(observed, expected, 5), "mesh light " + std::to_string(l), false);
  }
}

}  // namespace emission_distribution_test
}  // namespace nimbus::testing
