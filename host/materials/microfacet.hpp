// The Trowbridge-Reitz (GGX) microfacet distribution with Smith masking and visible-normal sampling
// (Heitz 2018), following the design of pbrt-v4 (section 9.6). Part of scattering.hpp; include that.
//
// The formulas are rearranged so that nothing divides by cos(theta): D and Lambda are written over
// x, y, z of the unit vector directly. That keeps alphas down to the 1e-4 smooth threshold accurate near
// the pole (where z rounds to 1) and keeps the visible-normal pdf finite at the horizon.
#pragma once

#include <nimbus/cpp/math.hpp>
#include "materials/local_frame.hpp"

namespace nimbus {

class TrowbridgeReitz {
 public:
  // Below this alpha a lobe is treated as a delta: D would exceed float range and no sampler could hit it.
  static constexpr float kSmoothAlpha = 1e-4f;

  // User-facing roughness in [0, 1] to alpha; squaring gives a perceptually even slider.
  static float roughness_to_alpha(float roughness) {
    return std::isfinite(roughness) ? sqr(clamp(roughness, 0.0f, 1.0f)) : 0.0f;
  }

  TrowbridgeReitz() = default;
  TrowbridgeReitz(float alpha_x, float alpha_y) : alpha_x_(sanitize(alpha_x)), alpha_y_(sanitize(alpha_y)) {
    // A rough lobe with one degenerate axis would divide by zero in D; give it the smallest usable alpha.
    if (!effectively_smooth()) {
      alpha_x_ = std::max(alpha_x_, kSmoothAlpha);
      alpha_y_ = std::max(alpha_y_, kSmoothAlpha);
    }
  }

  float alpha_x() const { return alpha_x_; }
  float alpha_y() const { return alpha_y_; }
  bool effectively_smooth() const { return std::max(alpha_x_, alpha_y_) < kSmoothAlpha; }

  // Distribution of microfacet normals wm (upper hemisphere, unit length), per solid angle, normalised so
  // that the projected area integrates to one: 1 / (pi ax ay cos^4 (1 + tan^2 (cos^2 phi / ax^2 +
  // sin^2 phi / ay^2))^2), with cos^4 folded into the square so that nothing divides by cos.
  float D(const Vec3f &wm) const {
    const float e = sqr(wm.x / alpha_x_) + sqr(wm.y / alpha_y_) + sqr(wm.z);
    return 1 / (kPi * alpha_x_ * alpha_y_ * e * e);
  }

  // Smith's auxiliary function; +Inf at the horizon (fully masked).
  float Lambda(const Vec3f &w) const {
    const float t = (sqr(alpha_x_ * w.x) + sqr(alpha_y_ * w.y)) / cos2_theta(w);  // alpha^2 tan^2
    if (!(t < kInfinity)) return kInfinity;
    // (sqrt(1 + t) - 1) / 2 without the cancellation at small t.
    return t / (2 * (1 + std::sqrt(1 + t)));
  }
  float G1(const Vec3f &w) const { return 1 / (1 + Lambda(w)); }
  // Height-correlated masking-shadowing.
  float G(const Vec3f &wo, const Vec3f &wi) const { return 1 / (1 + Lambda(wo) + Lambda(wi)); }

  // Density of the normals visible from w (either side of the surface; w is mirrored when below):
  // G1(w) / |cos w| * D(wm) * max(0, w . wm). G1(w) / |cos w| = 2 / (|cos w| + sqrt(cos^2 w + a^2)) stays
  // finite at the horizon.
  float D(const Vec3f &w, const Vec3f &wm) const {
    const float cos_wm = std::copysign(1.0f, w.z) * dot(w, wm);
    if (!(cos_wm > 0)) return 0;
    const float a2 = sqr(alpha_x_ * w.x) + sqr(alpha_y_ * w.y);
    const float g1_over_cos = 2 / (std::abs(w.z) + std::sqrt(sqr(w.z) + a2));
    return g1_over_cos * D(wm) * cos_wm;
  }
  // The pdf of sample_wm(w, .).
  float pdf(const Vec3f &w, const Vec3f &wm) const { return D(w, wm); }

  // A normal wm distributed as D(w, wm), always in the upper hemisphere (Heitz 2018, "Sampling the GGX
  // Distribution of Visible Normals"): stretch to the alpha = 1 configuration, sample the projected
  // hemisphere as a disk warped towards the visible half, unstretch.
  Vec3f sample_wm(Vec3f w, Vec2f u) const {
    if (w.z < 0) w = -w;
    const Vec3f wh = normalize(Vec3f(alpha_x_ * w.x, alpha_y_ * w.y, w.z));
    const float len2 = sqr(wh.x) + sqr(wh.y);
    const Vec3f t1 = len2 > 0 ? Vec3f(-wh.y, wh.x, 0) / std::sqrt(len2) : Vec3f(1, 0, 0);
    const Vec3f t2 = cross(wh, t1);
    const float r = std::sqrt(u.x), phi = 2 * kPi * u.y;
    const float px = r * std::cos(phi);
    float py = r * std::sin(phi);
    const float s = (1 + wh.z) / 2;
    py = (1 - s) * safe_sqrt(1 - px * px) + s * py;
    const float pz = safe_sqrt(1 - px * px - py * py);
    const Vec3f nh = t1 * px + t2 * py + wh * pz;
    // The clamp keeps wm off the horizon, where the unstretch would lose it.
    return normalize(Vec3f(alpha_x_ * nh.x, alpha_y_ * nh.y, std::max(1e-6f, nh.z)));
  }

 private:
  static float sanitize(float alpha) { return std::isfinite(alpha) ? std::max(alpha, 0.0f) : 0.0f; }

  float alpha_x_ = 0, alpha_y_ = 0;
};

}  // namespace nimbus
