// Motion blur in nimbus.pt: a render whose box, light or camera moves while the shutter is open equals
// the average of static renders at evenly spaced times within it (the film integrates over time), column
// band by column band, within the noise of both; and it differs from the scene frozen mid-way by far
// more, so the comparison can fail. nimbus.lt agrees with it. A scene that moves nothing draws no time:
// its image is the static one.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "support/render_support.hpp"

namespace nimbus::testing {
namespace motion_blur_test {

// A dark box over a lit floor, seen from above; `box` is the box's placement (transform or motion).
std::string scene(const std::string &box, const std::string &shutter) {
  return "render: { resolution: [48, 24], max_depth: 3 }\n"
         "camera: { position: [0, -0.01, 6], look_at: [0, 0, 0], up: [0, 1, 0], fov: 50" +
         shutter +
         " }\n"
         "materials:\n  white: { type: diffuse, albedo: 0.8 }\n  dark: { type: diffuse, albedo: 0.05 }\n"
         "objects:\n  - { shape: rectangle, size: [20, 20], material: white }\n"
         "  - { shape: box, size: [1, 1, 1], material: dark, " +
         box + " }\nlights:\n  - { type: point, position: [0, 0, 8], power: 2000 }\n";
}

RenderRequest request(uint64_t iterations, uint64_t seed) {
  RenderRequest r;
  r.integrator = "nimbus.pt", r.iterations = iterations, r.seed = seed;
  return r;
}

// Luminance-free mean of R over the columns [c0, c1) of all rows.
double band_mean(const ImageLayers &img, uint32_t c0, uint32_t c1) {
  const std::vector<float> &r = img.layers.at("beauty").data;
  const size_t channels = r.size() / (size_t(img.width) * img.height);
  double sum = 0;
  for (uint32_t y = 0; y < img.height; ++y)
    for (uint32_t x = c0; x < c1; ++x) sum += r[(size_t(y) * img.width + x) * channels];
  return sum / (double(c1 - c0) * img.height);
}

// A scene of the same floor, box and point light with its camera, box and light placed by the caller.
std::string placed_scene(const std::string &camera, const std::string &box, const std::string &light) {
  return "render: { resolution: [48, 24], max_depth: 3 }\n"
         "camera: { position: [0, -0.01, 6], look_at: [0, 0, 0], up: [0, 1, 0], fov: 50, shutter: { close: 1 "
         "}" +
         camera +
         " }\n"
         "materials:\n  white: { type: diffuse, albedo: 0.8 }\n  dark: { type: diffuse, albedo: 0.05 }\n"
         "objects:\n  - { shape: rectangle, size: [20, 20], material: white }\n"
         "  - { shape: box, size: [1, 1, 1], material: dark" +
         (box.empty() ? std::string(", transform: { translate: [0, 0, 0.5] }") : box) +
         " }\nlights:\n  - { type: point, power: 800" +
         (light.find("position") == std::string::npos ? ", position: [0, 0, 4]" : "") + light + " }\n";
}

// The render of `moving` (256 iterations, two seeds) against the mean of 16 renders of `frozen(x)` for x
// at the midpoints of 16 equal steps of [-1, 1] (32 iterations each), band by band; and against the scene
// frozen at x = 0, which must differ by far more.
void expect_average_of_frozen(const std::string &moving, const std::function<std::string(float)> &frozen) {
  SceneRenderer r;
  const auto blurred = r.render(moving, request(256, 1)), again = r.render(moving, request(256, 2));
  constexpr int kSteps = 16;
  std::vector<ImageLayers> still;
  for (int k = 0; k < kSteps; ++k)
    still.push_back(r.render(frozen(-1 + 2 * (float(k) + 0.5f) / kSteps), request(32, 100 + uint64_t(k))));
  const auto middle = r.render(frozen(0), request(256, 3));
  double worst = 0, contrast = 0;
  for (uint32_t c0 = 0; c0 < 48; c0 += 6) {
    double reference = 0;
    for (const ImageLayers &f : still) reference += band_mean(f, c0, c0 + 6) / kSteps;
    const double a = band_mean(blurred, c0, c0 + 6), b = band_mean(again, c0, c0 + 6);
    // As in PathTracerAveragesTheSceneOverTheShutter: 5 sigma plus 1 % for the time quadrature.
    const double sigma = std::max(std::abs(a - b) / std::sqrt(2.0), 0.005 * reference) * std::sqrt(2.0);
    EXPECT_NEAR(a, reference, 5 * sigma + 0.01 * reference) << "columns " << c0 << "-" << c0 + 6;
    worst = std::max(worst, std::abs(a - reference) / reference);
    contrast = std::max(contrast, std::abs(band_mean(middle, c0, c0 + 6) - reference) / reference);
  }
  EXPECT_GT(contrast, 5 * std::max(worst, 0.01)) << "worst band difference " << worst;
}

std::string vec(float x, float y, float z) {
  return "[" + std::to_string(x) + ", " + std::to_string(y) + ", " + std::to_string(z) + "]";
}

// A point light sweeping over the box: every shadow and highlight it casts, averaged (next-event
// estimation samples the light where it is at the path's time).
TEST(MotionBlur, MovingLightAveragesWhereItShines) {
  expect_average_of_frozen(placed_scene("", "",
                                        ", position: [0, 0, 4], motion: [{ time: 0, translate: [-3, 0, 0] }, "
                                        "{ time: 1, translate: [3, 0, 0] }]"),
                           [](float x) { return placed_scene("", "", ", position: " + vec(3 * x, 0, 4)); });
}

// A camera panning across the scene and turning as it goes: every view, averaged.
TEST(MotionBlur, MovingCameraAveragesWhatItSees) {
  expect_average_of_frozen(
      placed_scene(", motion: [{ time: 0, translate: [-1.5, 0, 0], rotate: [0, 0, -10] }, "
                   "{ time: 1, translate: [1.5, 0, 0], rotate: [0, 0, 10] }]",
                   "", ""),
      [](float x) {
        // The key's transform T(x) R(z) applied to the resting pose: position, look_at and up.
        const float a = radians(10 * x), c = std::cos(a), s = std::sin(a);
        const auto moved = [&](float px, float py, float pz) {
          return vec(c * px - s * py + 1.5f * x, s * px + c * py, pz);
        };
        return "render: { resolution: [48, 24], max_depth: 3 }\ncamera: { position: " + moved(0, -0.01f, 6) +
               ", look_at: " + moved(0, 0, 0) + ", up: " + vec(-s, c, 0) + ", fov: 50 }\n" +
               placed_scene("", "", "").substr(placed_scene("", "", "").find("materials:"));
      });
}

TEST(MotionBlur, PathTracerAveragesTheSceneOverTheShutter) {
  expect_average_of_frozen(
      placed_scene(
          "", ", motion: [{ time: 0, translate: [-2, 0, 0.5] }, { time: 1, translate: [2, 0, 0.5] }]", ""),
      [](float x) { return placed_scene("", ", transform: { translate: " + vec(2 * x, 0, 0.5) + " }", ""); });
}

// The same slide as mesh deformation (the box's corners at both ends of the shutter): vertices
// interpolated linearly sweep the same box at every time as the instance does, so with the same random
// numbers the two images agree to the float rounding of the two geometries.
TEST(MotionBlur, DeformingMeshSweepsLikeTheMovingInstance) {
  SceneRenderer r;
  const std::string shutter = ", shutter: { open: 0, close: 1 }";
  const auto moving = r.render(
      scene("motion: [{ time: 0, translate: [-2, 0, 0.5] }, { time: 1, translate: [2, 0, 0.5] }]", shutter),
      request(64, 1));
  std::string corners[2];
  for (int end = 0; end < 2; ++end) {
    corners[end] = "[";
    const float cx = end == 0 ? -2.0f : 2.0f;
    for (int i = 0; i < 8; ++i)
      corners[end] += std::string(i ? ", " : "") + "[" + std::to_string(cx + (i & 1 ? 0.5f : -0.5f)) + ", " +
                      std::to_string(i & 2 ? 0.5f : -0.5f) + ", " + std::to_string(i & 4 ? 1.0f : 0.0f) + "]";
    corners[end] += "]";
  }
  const std::string faces =
      "[[0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6], [0, 1, 5], [0, 5, 4], [2, 6, 7], "
      "[2, 7, 3], [0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5]]";
  const std::string mesh = "shape: mesh, positions: " + corners[0] + ", indices: " + faces + ", deform: [" +
                           corners[0] + ", " + corners[1] + "]";
  std::string yaml = scene("transform: { translate: [0, 0, 0.5] }", shutter);
  yaml.replace(yaml.find("shape: box, size: [1, 1, 1]"), std::string("shape: box, size: [1, 1, 1]").size(),
               mesh);
  yaml.replace(yaml.find(", transform: { translate: [0, 0, 0.5] }"),
               std::string(", transform: { translate: [0, 0, 0.5] }").size(), "");
  const auto deforming = r.render(yaml, request(64, 1));
  for (uint32_t c0 = 0; c0 < 48; c0 += 6) {
    const double a = band_mean(moving, c0, c0 + 6), b = band_mean(deforming, c0, c0 + 6);
    EXPECT_NEAR(a, b, 0.01 * a) << "columns " << c0 << "-" << c0 + 6;
  }
}

// nimbus.lt's image of `yaml` (two seeds of 128 iterations) against nimbus.pt's (two of 256), band by
// band, within both renders' noise (each measured from its two seeds, floored at 0.5 % of the band; 5
// sigma).
void expect_light_tracer_agrees(const std::string &yaml) {
  SceneRenderer r;
  RenderRequest lt = request(128, 1);
  lt.integrator = "nimbus.lt";
  const auto lt1 = r.render(yaml, lt);
  lt.seed = 2;
  const auto lt2 = r.render(yaml, lt);
  const auto pt1 = r.render(yaml, request(256, 3)), pt2 = r.render(yaml, request(256, 4));
  for (uint32_t c0 = 0; c0 < 48; c0 += 6) {
    const double l1 = band_mean(lt1, c0, c0 + 6), l2 = band_mean(lt2, c0, c0 + 6);
    const double p1 = band_mean(pt1, c0, c0 + 6), p2 = band_mean(pt2, c0, c0 + 6);
    const double sl = std::max(std::abs(l1 - l2) / 2, 0.005 * p1 / std::sqrt(2.0));
    const double sp = std::max(std::abs(p1 - p2) / 2, 0.005 * p1 / std::sqrt(2.0));
    EXPECT_NEAR((l1 + l2) / 2, (p1 + p2) / 2, 5 * std::sqrt(sl * sl + sp * sp))
        << "columns " << c0 << "-" << c0 + 6;
  }
}

// nimbus.lt gives its light paths times the same way: its blurred image agrees with nimbus.pt's.
TEST(MotionBlur, LightTracerAgreesWithThePathTracer) {
  expect_light_tracer_agrees(
      scene("motion: [{ time: 0, translate: [-2, 0, 0.5] }, { time: 1, translate: [2, 0, 0.5] }]",
            ", shutter: { open: 0, close: 1 }"));
}

// The light tracer connects to the camera where it is at the light path's time, and leaves a moving light
// where it is then: its image of a scene where camera, light and box all move agrees with nimbus.pt's.
TEST(MotionBlur, LightTracerAgreesWhenCameraAndLightMove) {
  expect_light_tracer_agrees(
      placed_scene(", motion: [{ time: 0, translate: [-1, 0, 0] }, { time: 1, translate: [1, 0, 0] }]",
                   ", motion: [{ time: 0, translate: [0, -1, 0.5] }, { time: 1, translate: [0, 1, 0.5] }]",
                   ", motion: [{ time: 0, translate: [-3, 0, 0] }, { time: 1, translate: [3, 0, 0] }]"));
}

TEST(MotionBlur, NothingMovesNoTimeIsDrawn) {
  // A shutter with a still scene, and a single motion key: the same image as without either.
  SceneRenderer r;
  const auto plain = r.render(scene("transform: { translate: [0, 0, 0.5] }", ""), request(4, 7));
  const auto shuttered =
      r.render(scene("transform: { translate: [0, 0, 0.5] }", ", shutter: { close: 1 }"), request(4, 7));
  EXPECT_EQ(plain.layers.at("beauty").data, shuttered.layers.at("beauty").data);
}

}  // namespace motion_blur_test
}  // namespace nimbus::testing
