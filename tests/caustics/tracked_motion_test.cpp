// The tracked case of motion blur (spec 7.1): a mirror and the camera move together under a fixed delta
// sun, so the patch of sunlight the mirror throws on the floor stands still in the image. Only photons
// render that patch (no camera path can reach a delta sun through a mirror). With lookups that merge
// photons of similar time its edge is about as sharp as in the static render; lookups that ignore time
// smear it over the distance the mirror travels. The edge width is the 10-90 % rise of the patch's
// column profile, averaged over its middle rows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "sphere_scenes.hpp"

namespace nimbus::testing {
namespace tracked_motion_test {

constexpr uint32_t kWidth = 96, kHeight = 64;

// The mirror tilted to throw the low sun down onto the floor beside it, seen from above; `moving`: the
// mirror and the camera travel 0.4 along x together while the shutter is open.
std::string mirror_scene(bool moving) {
  const auto at = [](float x) {
    return "rotate: [0, -121, 0], translate: [" + std::to_string(x) + ", 0, 1.5]";
  };
  const std::string camera =
      moving ? ", shutter: { close: 1 }, motion: [{ time: 0 }, { time: 1, translate: [0.4, 0, 0] }]" : "";
  const std::string mirror = moving ? "motion: [{ time: 0, " + at(0) + " }, { time: 1, " + at(0.4f) + " }]"
                                    : "transform: { " + at(0) + " }";
  return "render: { resolution: [" + std::to_string(kWidth) + ", " + std::to_string(kHeight) +
         "], max_depth: 6 }\n"
         "camera: { position: [-0.8, 0, 5], look_at: [-0.8, 0, 0], up: [0, 1, 0], fov: 40" +
         camera +
         " }\n"
         "materials:\n  floor: { type: diffuse, albedo: 0.8 }\n  mirror: { type: conductor, reflectance: 1 "
         "}\n"
         "objects:\n  - { shape: rectangle, size: [20, 20], material: floor }\n"
         "  - { shape: rectangle, size: [0.6, 0.6], material: mirror, " +
         mirror +
         " }\n"
         "lights:\n  - { type: sun, direction: [1, 0, -0.05], irradiance: 3, angular_diameter: 0 }\n";
}

// The 10-90 % width (pixels) of the steeper of the patch's left and right edges, along columns, from the
// mean profile of the rows through its middle third.
double edge_width(const ImageLayers &img) {
  const std::vector<float> &d = img.layers.at("beauty").data;
  std::vector<double> column(kWidth, 0.0), row(kHeight, 0.0);
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) {
      const double v = luminance(Rgb::load(&d[3 * (size_t(y) * kWidth + x)]));
      row[y] += v;
    }
  // The patch's rows: those brighter than half the brightest row.
  const double top = *std::max_element(row.begin(), row.end());
  uint32_t y0 = kHeight, y1 = 0;
  for (uint32_t y = 0; y < kHeight; ++y)
    if (row[y] > 0.5 * top) y0 = std::min(y0, y), y1 = std::max(y1, y);
  const uint32_t third = (y1 - y0 + 1) / 3;
  for (uint32_t y = y0 + third; y <= y1 - third; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) column[x] += luminance(Rgb::load(&d[3 * (size_t(y) * kWidth + x)]));
  const double peak = *std::max_element(column.begin(), column.end());
  std::vector<double> sorted(column);
  std::sort(sorted.begin(), sorted.end());
  const double floor = sorted[kWidth / 10], plateau = peak;  // background and the patch's level
  const auto crossing = [&](double level, int from, int step) {
    for (int x = from; x >= 0 && x < int(kWidth) - 1; x += step) {
      const double a = column[size_t(x)], b = column[size_t(x + step)];
      if ((a - level) * (b - level) <= 0 && a != b) return x + step * (level - a) / (b - a);
    }
    return double(from);
  };
  const int centre = int(std::max_element(column.begin(), column.end()) - column.begin());
  const double lo = floor + 0.1 * (plateau - floor), hi = floor + 0.9 * (plateau - floor);
  const double left = std::abs(crossing(lo, centre, -1) - crossing(hi, centre, -1));
  const double right = std::abs(crossing(lo, centre, 1) - crossing(hi, centre, 1));
  return std::min(left, right);
}

TEST(CausticsTrackedMotion, CausticStaysSharpOnlyWhenLookupsMatchTime) {
  SceneRenderer r;
  const auto still = r.render(mirror_scene(false), request("nimbus.caustics", 64, 11));
  RenderRequest matched = request("nimbus.caustics", 64, 12), ignored = request("nimbus.caustics", 64, 13);
  ignored.options = {{"photon_times", "ignored"}};
  const auto tracked = r.render(mirror_scene(true), matched);
  const auto smeared = r.render(mirror_scene(true), ignored);
  const double w_still = edge_width(still), w_tracked = edge_width(tracked), w_smeared = edge_width(smeared);
  std::printf("edge width (pixels): still %.2f, tracked %.2f, lookups ignoring time %.2f\n", w_still,
              w_tracked, w_smeared);
  EXPECT_GT(stat(tracked, "caustics_photon_paths"), 0.0);
  // The distance the mirror travels, in pixels of the 5 m high camera's 40 degree view: 10.5.
  const double travel = 0.4 / (2 * 5 * std::tan(radians(20.0f)) / kWidth);
  // Time-matched lookups blur the edge by the window's share of the travel (2h = 1/4 at the first
  // pass, shrinking): within a quarter of the travel of the still edge. Lookups that ignore time spread
  // it over the whole travel (a box of 10.5 pixels rises 10-90 % over 8.4): at least half the travel more.
  EXPECT_LT(w_tracked, w_still + 0.25 * travel);
  EXPECT_GT(w_smeared, w_still + 0.5 * travel);
}

}  // namespace tracked_motion_test
}  // namespace nimbus::testing
