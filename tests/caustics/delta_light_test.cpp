// Caustics of small, far delta lights against an independent reference (reference_light_tracer.hpp):
// a 5 cm glass ball on a large floor, lit from 10 m by a point, spot or delta sun light (or through a
// mirror), seen straight down so that each pixel is a floor square. Path tracing cannot render these
// caustics at all, so whatever light the solver's photons fail to carry is simply missing: a solver
// that learns where to aim only from its first (probe) pass misses a ball its probe did not hit.
//
// For each scene: the mean over seeds of the region mean at kIterations must match the reference within
// 3 combined standard errors, the caustic must be there (the region mean well above its value without
// the ball's light), and the region's relMSE must fall from kFewIterations to kIterations.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "caustics/reference_light_tracer.hpp"
#include "support/render_support.hpp"

namespace nimbus::testing {
namespace delta_light_test {

namespace ref = reference;

constexpr int kSeeds = 4;
constexpr uint64_t kIterations = 256;    // region means, and 4N for the error's fall
constexpr uint64_t kFewIterations = 64;  // N
constexpr int kBatches = 16;             // reference batches: their spread is the reference's SE

struct Region {
  int x0, y0, x1, y1;
  int pixels() const { return (x1 - x0) * (y1 - y0); }
};

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}
std::string vec(ref::V3 v) { return "[" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + "]"; }

// The scene file of a reference scene, from the same numbers, so that both render one scene. aperture:
// a thin lens of that radius focused on the floor, whose points every lens point sees at the pinhole's
// raster position, so the reference (a pinhole's) holds for pixels that see only floor through the
// whole lens.
std::string scene_yaml(const ref::Scene &s, double aperture = 0) {
  std::string y = "render: { resolution: [" + std::to_string(s.width) + ", " + std::to_string(s.height) +
                  "], max_depth: " + std::to_string(s.max_depth) + ", filter: box }\n";
  y += "camera: { position: " + vec(s.eye) + ", look_at: " + vec({s.eye.x, s.eye.y, 0}) +
       ", up: [0, 1, 0], fov: " + num(s.fov_deg);
  if (aperture > 0) y += ", aperture: " + num(aperture) + ", focus_distance: " + num(s.eye.z);
  y += " }\n";
  y += "materials:\n  floor: { type: diffuse, albedo: " + num(s.albedo) +
       " }\n  glass: { type: dielectric, ior: " + num(s.ior) + " }\n  black: { type: diffuse, albedo: 0 }\n";
  for (size_t i = 0; i < s.mirrors.size(); ++i)
    y += "  mirror" + std::to_string(i) +
         ": { type: conductor, reflectance: " + num(s.mirrors[i].reflectance) + " }\n";
  y += "objects:\n  - { shape: rectangle, size: [" + num(2 * s.floor_half) + ", " + num(2 * s.floor_half) +
       "], material: floor }\n";
  y += "  - { shape: sphere, center: " + vec(s.ball) + ", radius: " + num(s.radius) + ", material: glass }\n";
  for (size_t i = 0; i < s.mirrors.size(); ++i) {  // the unit square, [-0.5, 0.5]^2, onto the mirror
    const ref::Mirror &m = s.mirrors[i];
    const ref::V3 u = m.half_u * 2, v = m.half_v * 2, n = ref::unit(ref::cross(u, v)), c = m.center;
    y += "  - { shape: rectangle, size: [1, 1], material: mirror" + std::to_string(i) +
         ", transform: { matrix: [" + num(u.x) + ", " + num(v.x) + ", " + num(n.x) + ", " + num(c.x) + ", " +
         num(u.y) + ", " + num(v.y) + ", " + num(n.y) + ", " + num(c.y) + ", " + num(u.z) + ", " + num(v.z) +
         ", " + num(n.z) + ", " + num(c.z) + ", 0, 0, 0, 1] } }\n";
  }
  for (const ref::Box &b : s.blockers)
    y += "  - { shape: box, size: " + vec(b.hi - b.lo) +
         ", material: black, transform: { translate: " + vec((b.lo + b.hi) * 0.5) + " } }\n";
  const std::string I = num(s.intensity);
  y += "lights:\n  - { ";
  if (s.light == ref::LightKind::Point)
    y += "type: point, position: " + vec(s.position) + ", intensity: " + I;
  if (s.light == ref::LightKind::Spot)
    y += "type: spot, position: " + vec(s.position) + ", direction: " + vec(s.direction) +
         ", cone: " + num(s.cone_deg) + ", softness: " + num(s.softness_deg) + ", intensity: " + I;
  if (s.light == ref::LightKind::Sun)
    y += "type: sun, direction: " + vec(s.direction) + ", irradiance: " + I + ", angular_diameter: 0";
  return y + " }\n";
}

// The hall: a 40 m floor (albedo 0.5), a glass ball of radius 5 cm resting on it at the origin, the light
// 10 m from the ball at 30 degrees elevation, travelling along +x. A ball resting on the floor focuses
// light about half a radius beyond its far side: at 40-60 degrees that spot lies under the ball as seen
// from above, at 30 degrees 95 % of the caustic's flux lands outside it. The camera, 0.5 m up, sees a
// 17.6 x 13.2 cm patch around the caustic (2.75 mm pixels) and the ball at its left edge. The ball covers
// (R / 2D)^2 = 6e-6 of a point light's sphere of directions: 0.4 of the solver's 2^16 probe paths.
constexpr double kElevation = 30 * ref::kPi / 180, kDistance = 10, kRadius = 0.05;

ref::Scene hall(ref::LightKind light) {
  ref::Scene s;
  s.radius = kRadius, s.ball = {0, 0, kRadius};
  s.light = light;
  s.position = s.ball + ref::V3{-std::cos(kElevation), 0, std::sin(kElevation)} * kDistance;
  s.direction = {std::cos(kElevation), 0, -std::sin(kElevation)};
  s.intensity = light == ref::LightKind::Sun ? 1 : kDistance * kDistance;  // 0.5 W/m^2 on the open floor
  s.eye = {0.09, 0, 0.5}, s.fov_deg = 20, s.width = 64, s.height = 48, s.max_depth = 10;
  // The reference's photons: half at the ball, the rest at the image and at the floor around the ball
  // (whose light the ball brings into the image), 2 % everywhere.
  s.aims = {{s.ball, kRadius * 1.001, 0.5}, s.footprint(0.25), {s.ball, 5 * kRadius, 0.15}};
  return s;
}

// The spot at the same place, its axis 20 degrees below the ball, inside the soft edge of a 30 degree
// cone (full up to 10): the ball gets 0.68 of the axis intensity, by the smoothstep the docs give.
ref::Scene spot() {
  ref::Scene s = hall(ref::LightKind::Spot);
  s.direction = {std::cos(kElevation + 20 * ref::kPi / 180), 0, -std::sin(kElevation + 20 * ref::kPi / 180)};
  s.cone_deg = 30, s.softness_deg = 20;
  return s;
}

// The light and the ball on either side of a blocker (a black box whose shadow covers the ball and the
// image): the ball sees the light only in a 1.2 x 1 m mirror, the plane x = -1 facing +x, as the far
// point light's virtual image (the light mirrored in that plane). So the image is the far point light's,
// carried by one more specular bounce, and the probe meets the mirror (~70 paths) but not the ball.
ref::Scene behind_mirror() {
  ref::Scene s = hall(ref::LightKind::Point);
  const auto mirrored = [](ref::V3 p) { return ref::V3{-2 - p.x, p.y, p.z}; };
  s.position = mirrored(s.position);
  s.mirrors = {{{-1, 0, 0.65}, {0, 0.6, 0}, {0, 0, 0.5}, 1.0}};
  const ref::V3 mid = (s.position + s.ball) * 0.5, half{0.25, 0.25, 0.25};
  s.blockers = {{mid - half, mid + half}};
  const ref::Aim image = s.footprint(0.25);
  s.aims = {{mirrored(s.ball), kRadius * 1.001, 0.5},
            {mirrored(image.center), image.radius, 0.25},
            {mirrored(s.ball), 5 * kRadius, 0.1},
            {s.ball, 5 * kRadius, 0.05}};
  return s;
}

// The caustic's core and some margin (81 % of its visible light), all floor: the ball's shadow, so that
// without the caustic the region would be black (it holds no direct light).
constexpr Region kCaustic{16, 14, 42, 34};

// Region means and per-pixel values of the reference over its batches.
struct Reference {
  double mean = 0, se = 0, without_ball = 0;  // region mean, its SE, and the part not through the ball
  std::vector<double> pixel, pixel_var;       // per region pixel: mean and variance of the mean
};

Reference summarize(const ref::Image &img, const Region &r) {
  Reference out;
  std::vector<double> means(img.batches, 0);
  double glass = 0;
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) {
      double s = 0, s2 = 0;
      for (int b = 0; b < img.batches; ++b) {
        const double v = img.value(b, x, y);
        s += v, s2 += v * v, means[b] += v / r.pixels();
        glass += img.glass[(size_t(b) * img.height + y) * img.width + x] / (img.batches * r.pixels());
      }
      const double m = s / img.batches;
      out.pixel.push_back(m);
      out.pixel_var.push_back((s2 / img.batches - m * m) / (img.batches - 1));
    }
  double s = 0, s2 = 0;
  for (const double m : means) s += m, s2 += m * m;
  out.mean = s / img.batches;
  out.se = std::sqrt((s2 / img.batches - out.mean * out.mean) / (img.batches - 1));
  out.without_ball = out.mean - glass;
  return out;
}

double region_mean(const ImageLayers &img, const Region &r) {
  const std::vector<float> &d = img.layers.at("beauty").data;
  double s = 0;
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) s += luminance(Rgb::load(&d[3 * (size_t(y) * img.width + x)]));
  return s / r.pixels();
}

// The region's relMSE against the reference: sum (solver - ref)^2 / sum ref^2 over its pixels, less the
// reference's own variance (E (s - r)^2 = (s - true)^2 + var r), so that only the solver's error is left.
double region_rel_mse(const ImageLayers &img, const Region &r, const Reference &rf) {
  const std::vector<float> &d = img.layers.at("beauty").data;
  double num = 0, den = 0;
  size_t i = 0;
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x, ++i) {
      const double s = luminance(Rgb::load(&d[3 * (size_t(y) * img.width + x)]));
      num += (s - rf.pixel[i]) * (s - rf.pixel[i]) - rf.pixel_var[i], den += rf.pixel[i] * rf.pixel[i];
    }
  return num / den;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : (v[v.size() / 2 - 1] + v[v.size() / 2]) / 2;
}

double stat(const ImageLayers &img, const std::string &name) {
  const auto it = img.numbers.find("nimbus:stat:" + name);
  return it == img.numbers.end() ? -1.0 : it->second;
}

RenderRequest request(uint64_t iterations, uint64_t seed) {
  RenderRequest q;
  q.integrator = "nimbus.caustics";
  q.iterations = iterations;
  q.seed = seed;
  return q;
}

// Reference photon paths: a region mean SE of ~0.1 % and ~3 % per pixel, in about a second.
constexpr uint64_t kPhotons = uint64_t(1) << 22;

// kernel_bias: the merge kernel's blur at kIterations, as a share of the reference (0 where the region holds
// the whole caustic and its blur stays inside).
void compare_with_reference(const char *name, const ref::Scene &scene, const Region &region,
                            double kernel_bias = 0, double aperture = 0) {
  const auto start = std::chrono::steady_clock::now();
  // The reference holds floor radiance only: every pixel of the region must see nothing but floor.
  for (int y = region.y0; y < region.y1; ++y)
    for (int x = region.x0; x < region.x1; ++x)
      ASSERT_TRUE(ref::pixel_sees_floor_only(scene, x, y)) << "pixel " << x << ", " << y;
  const Reference rf = summarize(ref::trace(scene, kPhotons, kBatches, 7), region);
  const auto traced = std::chrono::steady_clock::now();
  SceneRenderer renderer;
  const std::string yaml = scene_yaml(scene, aperture);
  std::vector<double> means, err_few, err_many;
  for (int k = 0; k < kSeeds; ++k) {
    const ImageLayers many = renderer.render(yaml, request(kIterations, 1 + k));
    const ImageLayers few = renderer.render(yaml, request(kFewIterations, 101 + k));
    means.push_back(region_mean(many, region));
    err_many.push_back(region_rel_mse(many, region, rf));
    err_few.push_back(region_rel_mse(few, region, rf));
    // The photon statistics tell a dormant or backed-off solver (few passes, no photons) from a noisy one.
    std::printf(
        "  seed %d: region mean %.5f; relMSE %.4g at %llu iterations, %.4g at %llu; %.0f photon passes, "
        "%.0f paths, %.0f photons\n",
        1 + k, means.back(), err_few.back(), (unsigned long long)kFewIterations, err_many.back(),
        (unsigned long long)kIterations, stat(many, "caustics_photon_passes"),
        stat(many, "caustics_photon_paths"), stat(many, "caustics_photons"));
  }
  double s = 0, s2 = 0;
  for (const double m : means) s += m, s2 += m * m;
  const double mean = s / kSeeds, se = std::sqrt((s2 / kSeeds - mean * mean) / (kSeeds - 1));
  const double combined = std::hypot(se, rf.se);
  const double fall = median(err_few) / median(err_many);
  const auto end = std::chrono::steady_clock::now();
  std::printf(
      "%s: reference %.5f (SE %.5f, %.1f %% relative), %.5f without the ball's light (caustic share %.1f "
      "%%)\n",
      name, rf.mean, rf.se, 100 * rf.se / rf.mean, rf.without_ball, 100 * (1 - rf.without_ball / rf.mean));
  std::printf("  solver at %llu iterations, seeds:", (unsigned long long)kIterations);
  for (const double m : means) std::printf(" %.5f", m);
  std::printf("; mean %.5f (SE %.5f), %.2f combined SEs from the reference, ratio %.4f\n", mean, se,
              (mean - rf.mean) / combined, mean / rf.mean);
  std::printf("  relMSE (median of %d seeds) %.4g at %llu iterations, %.4g at %llu: falls %.2fx\n", kSeeds,
              median(err_few), (unsigned long long)kFewIterations, median(err_many),
              (unsigned long long)kIterations, fall);
  std::printf("  time: reference %.1f s, renders %.1f s\n",
              std::chrono::duration<double>(traced - start).count(),
              std::chrono::duration<double>(end - traced).count());
  // The combined standard error: the solver's (sample SE over kSeeds renders) and the reference's (over
  // kBatches batches, ~0.1 %, so the solver's dominates), plus the kernel's bias. The solver's SE is
  // estimated from kSeeds = 4 renders, so the bound is Student's t for 3 degrees of freedom at the
  // coverage of 3 sigma (two-sided 99.73 %): 9.22 SEs, still ~0.7 % of the mean here.
  static_assert(kSeeds == 4, "the t quantile below is for 3 degrees of freedom");
  constexpr double kT3 = 9.22;
  EXPECT_NEAR(mean, rf.mean, kT3 * combined + kernel_bias * rf.mean);
  // The caustic is there in every render: at least half of the light the ball adds to the region (a
  // render's region mean is within ~10 % of the reference when the solver finds the caustic, and at the
  // value without it when it does not, so the mean over seeds alone could hide a miss).
  for (int k = 0; k < kSeeds; ++k)
    EXPECT_GT(means[k] - rf.without_ball, 0.5 * (rf.mean - rf.without_ball)) << "seed " << 1 + k;
  // A consistent solver's region relMSE falls with iterations. The budget keeps photon paths per camera
  // path near its optimum, so 4x iterations bring ~4x photon paths in ~4x passes: photon noise falls as
  // (photon paths r^2)^-1 ~ 4^-0.75 (r^2 ~ j^-0.25), the kernel bias squared as 4^-0.5, so 2x to 2.8x,
  // less where the start-up maps (the probe's, serving many iterations) still weigh. Each relMSE averages
  // 520 pixels (less the reference's own variance); 1.3 leaves room for the median of 4 heavy-tailed
  // renders. A missing caustic gives relMSE ~1 at both counts.
  EXPECT_GT(fall, 1.3);
}

TEST(CausticsDeltaLights, FarPointLight) {
  compare_with_reference("far point light", hall(ref::LightKind::Point), kCaustic);
}

// The same through a thin lens of 1 cm radius focused on the floor: photons splatted to the lens
// (photon_splats.hpp) connect to a sampled lens point, and camera paths start from one. The region
// leaves out the columns nearest the ball, which it hides from part of the lens.
TEST(CausticsDeltaLights, FarPointLightThroughAThinLens) {
  compare_with_reference("far point light, thin lens", hall(ref::LightKind::Point), Region{20, 14, 42, 34}, 0,
                         0.01);
}

TEST(CausticsDeltaLights, FarSpotLight) { compare_with_reference("far spot light", spot(), kCaustic); }

TEST(CausticsDeltaLights, DeltaSun) {
  compare_with_reference("delta sun", hall(ref::LightKind::Sun), kCaustic);
}

TEST(CausticsDeltaLights, BallBehindMirror) {
  // The region holds 81 % of the caustic's light: at 256 iterations the kernel (radius still ~half its
  // first) spreads ~1 % of it across the region's edge (measured: -0.9 % over 4 seeds).
  compare_with_reference("ball behind a mirror", behind_mirror(), kCaustic, 0.015);
}

}  // namespace delta_light_test
}  // namespace nimbus::testing
