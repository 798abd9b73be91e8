// Transforms that change over the shutter (motion blur). A key's affine transform is decomposed as
// Embree's RTCQuaternionDecomposition does it: M = T R S, T a translation, R a rotation (unit
// quaternion), S upper triangular (scale, skew and shift). Between keys S and T move linearly and R by
// spherical interpolation along the shorter arc, as Embree interpolates an instance's time steps, so the
// host's own evaluation (normals and positions of hits at a ray's time) follows the geometry Embree
// intersects. Embree spaces time steps evenly: evenly spaced keys are its steps, keys at other times are
// resampled onto an even grid with at least 4 steps per key interval, and the host evaluates that grid.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/transform.hpp"

namespace nimbus {

struct Quaternion {
  float r = 1, i = 0, j = 0, k = 0;  // r + i·i + j·j + k·k

  // The unit quaternion of a proper rotation matrix (rows of the linear part).
  static Quaternion from_rotation(const float m[3][3]) {
    Quaternion q;
    const float trace = m[0][0] + m[1][1] + m[2][2];
    if (trace >= 0) {
      const float s = std::sqrt(trace + 1) * 2;
      q = {0.25f * s, (m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s};
    } else if (m[0][0] >= m[1][1] && m[0][0] >= m[2][2]) {
      const float s = std::sqrt(1 + m[0][0] - m[1][1] - m[2][2]) * 2;
      q = {(m[2][1] - m[1][2]) / s, 0.25f * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s};
    } else if (m[1][1] >= m[2][2]) {
      const float s = std::sqrt(1 + m[1][1] - m[0][0] - m[2][2]) * 2;
      q = {(m[0][2] - m[2][0]) / s, (m[0][1] + m[1][0]) / s, 0.25f * s, (m[1][2] + m[2][1]) / s};
    } else {
      const float s = std::sqrt(1 + m[2][2] - m[0][0] - m[1][1]) * 2;
      q = {(m[1][0] - m[0][1]) / s, (m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25f * s};
    }
    return q.normalized();
  }
  float dot(const Quaternion &o) const { return r * o.r + i * o.i + j * o.j + k * o.k; }
  Quaternion normalized() const {
    const float n = std::sqrt(dot(*this));
    return n > 0 ? Quaternion{r / n, i / n, j / n, k / n} : Quaternion{};
  }
  // Rows of the rotation matrix.
  void to_rotation(float m[3][3]) const {
    m[0][0] = 1 - 2 * (j * j + k * k), m[0][1] = 2 * (i * j - r * k), m[0][2] = 2 * (i * k + r * j);
    m[1][0] = 2 * (i * j + r * k), m[1][1] = 1 - 2 * (i * i + k * k), m[1][2] = 2 * (j * k - r * i);
    m[2][0] = 2 * (i * k - r * j), m[2][1] = 2 * (j * k + r * i), m[2][2] = 1 - 2 * (i * i + j * j);
  }
  // Spherical interpolation along the shorter arc (Embree's rule for time steps).
  static Quaternion slerp(const Quaternion &a, Quaternion b, float t) {
    float c = a.dot(b);
    if (c < 0) b = {-b.r, -b.i, -b.j, -b.k}, c = -c;
    if (c > 0.9995f)
      return Quaternion{a.r + t * (b.r - a.r), a.i + t * (b.i - a.i), a.j + t * (b.j - a.j),
                        a.k + t * (b.k - a.k)}
          .normalized();
    const float theta = std::acos(std::min(c, 1.0f)), s = std::sin(theta);
    const float wa = std::sin((1 - t) * theta) / s, wb = std::sin(t * theta) / s;
    return Quaternion{wa * a.r + wb * b.r, wa * a.i + wb * b.i, wa * a.j + wb * b.j, wa * a.k + wb * b.k}
        .normalized();
  }
};

// Where `fraction` (in [0, 1] over the shutter) falls on an even grid of `steps` >= 2 time steps: the step
// before it and how far towards the next, as Embree places a ray's time between time steps.
struct GridPosition {
  size_t step;
  float between;
};
inline GridPosition grid_position(float fraction, size_t steps) {
  const float x = std::clamp(fraction, 0.0f, 1.0f) * float(steps - 1);
  const size_t k = std::min(size_t(x), steps - 2);
  return {k, x - float(k)};
}

// One affine transform as T R S (the fields of Embree's RTCQuaternionDecomposition).
struct Decomposed {
  std::array<float, 6> scale_skew{1, 1, 1, 0, 0, 0};  // sx, sy, sz, skew_xy, skew_xz, skew_yz
  std::array<float, 3> shift{0, 0, 0};
  Quaternion rotation;
  std::array<float, 3> translation{0, 0, 0};

  // Gram-Schmidt on the columns of the linear part gives R (made proper by flipping the sign of its last
  // column and of S's last row when the transform mirrors) and S = R^T M.
  static Decomposed of(const Transform &m) {
    float a[3][3];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) a[r][c] = m(r, c);
    Vec3f col[3] = {{a[0][0], a[1][0], a[2][0]}, {a[0][1], a[1][1], a[2][1]}, {a[0][2], a[1][2], a[2][2]}};
    Vec3f q[3];
    q[0] = normalize(col[0]);
    q[1] = normalize(col[1] - q[0] * dot(q[0], col[1]));
    q[2] = cross(q[0], q[1]);  // proper rotation; a mirror shows as a negative sz
    Decomposed d;
    d.scale_skew = {dot(q[0], col[0]), dot(q[1], col[1]), dot(q[2], col[2]),
                    dot(q[0], col[1]), dot(q[0], col[2]), dot(q[1], col[2])};
    float rot[3][3];
    for (int r = 0; r < 3; ++r) rot[r][0] = q[0][r], rot[r][1] = q[1][r], rot[r][2] = q[2][r];
    d.rotation = Quaternion::from_rotation(rot);
    d.translation = {m(0, 3), m(1, 3), m(2, 3)};
    return d;
  }
  Transform matrix() const {
    float rot[3][3];
    rotation.to_rotation(rot);
    const float s[3][4] = {{scale_skew[0], scale_skew[3], scale_skew[4], shift[0]},
                           {0, scale_skew[1], scale_skew[5], shift[1]},
                           {0, 0, scale_skew[2], shift[2]}};
    std::array<float, 16> m{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1};
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) {
        double v = 0;
        for (int k = 0; k < 3; ++k) v += double(rot[r][k]) * s[k][c];
        m[r * 4 + c] = float(v);
      }
      m[r * 4 + 3] += translation[size_t(r)];
    }
    return Transform(m);
  }
  static Decomposed lerp(const Decomposed &a, const Decomposed &b, float t) {
    Decomposed d;
    for (size_t n = 0; n < 6; ++n)
      d.scale_skew[n] = a.scale_skew[n] + t * (b.scale_skew[n] - a.scale_skew[n]);
    for (size_t n = 0; n < 3; ++n) {
      d.shift[n] = a.shift[n] + t * (b.shift[n] - a.shift[n]);
      d.translation[n] = a.translation[n] + t * (b.translation[n] - a.translation[n]);
    }
    d.rotation = Quaternion::slerp(a.rotation, b.rotation, t);
    return d;
  }
};

// A transform keyed over the shutter [open, close]: steps evenly spaced over it, each decomposed.
class MotionTransform {
 public:
  struct Key {
    float time;
    Transform transform;
  };
  // A transform that never moves.
  explicit MotionTransform(const Transform &t = {}) : open_(0), close_(0), steps_{Decomposed::of(t)} {}
  // keys: times increasing (the parser checks it), within [open, close]. Before the first key and after
  // the last the transform holds still.
  MotionTransform(const std::vector<Key> &keys, float open, float close) : open_(open), close_(close) {
    if (keys.size() < 2 || !(close > open)) {
      steps_ = {Decomposed::of(keys.empty() ? Transform{} : keys.front().transform)};
      return;
    }
    std::vector<Decomposed> at_keys;
    for (const Key &k : keys) at_keys.push_back(Decomposed::of(k.transform));
    const uint32_t n = grid_intervals(keys, open, close);
    for (uint32_t s = 0; s <= n; ++s) {
      const float t = open + (close - open) * float(s) / float(n);
      size_t i = size_t(
          std::upper_bound(keys.begin(), keys.end(), t, [](float v, const Key &k) { return v < k.time; }) -
          keys.begin());
      if (i == 0)
        steps_.push_back(at_keys.front());
      else if (i == keys.size())
        steps_.push_back(at_keys.back());
      else {
        const float u = (t - keys[i - 1].time) / (keys[i].time - keys[i - 1].time);
        steps_.push_back(Decomposed::lerp(at_keys[i - 1], at_keys[i], u));
      }
    }
  }

  bool moves() const { return steps_.size() > 1; }
  float open() const { return open_; }
  float close() const { return close_; }
  // Embree's time steps (evenly spaced over [open, close]).
  const std::vector<Decomposed> &steps() const { return steps_; }
  // The transform at scene time t (held still outside the shutter).
  Transform at(float t) const {
    if (!moves()) return steps_.front().matrix();
    const GridPosition g = grid_position((t - open_) / (close_ - open_), steps_.size());
    return Decomposed::lerp(steps_[g.step], steps_[g.step + 1], g.between).matrix();
  }

 private:
  // Intervals of the even grid: the keys' own when they are evenly spaced, else enough that each key
  // interval spans at least 4 steps (at most 256).
  static uint32_t grid_intervals(const std::vector<Key> &keys, float open, float close) {
    const float span = close - open;
    const uint32_t n = uint32_t(keys.size() - 1);
    bool even = std::abs(keys.front().time - open) <= 1e-6f * span &&
                std::abs(keys.back().time - close) <= 1e-6f * span;
    float gap = span;
    for (size_t i = 1; i < keys.size(); ++i) {
      gap = std::min(gap, keys[i].time - keys[i - 1].time);
      even = even && std::abs(keys[i].time - (open + span * float(i) / float(n))) <= 1e-5f * span;
    }
    if (even) return n;
    return uint32_t(std::clamp(std::ceil(4 * span / std::max(gap, 1e-6f * span)), 1.0f, 256.0f));
  }

  float open_ = 0, close_ = 0;
  std::vector<Decomposed> steps_;
};

}  // namespace nimbus
