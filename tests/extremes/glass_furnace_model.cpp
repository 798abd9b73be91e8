#include "glass_furnace_model.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "support/ggx_reference.hpp"

namespace nimbus::extremes {

namespace {

using reference::axpy;
using reference::dot3;
using reference::scale;
using reference::unit;
using reference::V3;

constexpr double kPi = 3.14159265358979323846;
constexpr int kMaxBounces = 100;
constexpr double kEps = 1e-7;

// SplitMix64 (Steele et al. 2014): uniform doubles in [0, 1), enough for a test-side estimate.
struct Rng {
  uint64_t s;
  double next() {
    uint64_t z = (s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return double((z ^ (z >> 31)) >> 11) * 0x1p-53;
  }
};

struct Hit {
  double t;
  V3 normal;  // outward
};

std::optional<Hit> hit_unit_sphere(const V3 &o, const V3 &d) {
  const double b = dot3(o, d), c = dot3(o, o) - 1, disc = b * b - c;
  if (disc < 0) return std::nullopt;
  const double r = std::sqrt(disc);
  for (double t : {-b - r, -b + r})
    if (t > kEps) return Hit{t, axpy(t, d, o)};
  return std::nullopt;
}

// The slab: `shape: box, size: [1.6, 0.25, 0.7]`, rotated by R = Rz(10) Ry(0) Rx(25) (degrees, the scene
// format's fixed-axis order) and moved to (0.2, -1.7, -0.6).
struct Slab {
  V3 axis[3], center{0.2, -1.7, -0.6};
  double half[3] = {0.8, 0.125, 0.35};
  Slab() {
    const double a = 25 * kPi / 180, c = 10 * kPi / 180;
    // Columns of Rz(c) Rx(a): the box's local x, y and z axes in the world.
    axis[0] = {std::cos(c), std::sin(c), 0};
    axis[1] = {-std::sin(c) * std::cos(a), std::cos(c) * std::cos(a), std::sin(a)};
    axis[2] = {std::sin(c) * std::sin(a), -std::cos(c) * std::sin(a), std::cos(a)};
  }
  std::optional<Hit> hit(const V3 &o, const V3 &d) const {
    const V3 p = axpy(-1, center, o);
    double t0 = -1e300, t1 = 1e300;
    int a0 = 0, a1 = 0;
    double s0 = 1, s1 = 1;
    for (int i = 0; i < 3; ++i) {
      const double po = dot3(p, axis[i]), dd = dot3(d, axis[i]);
      if (dd == 0) {
        if (std::abs(po) > half[i]) return std::nullopt;
        continue;
      }
      double ta = (-half[i] - po) / dd, tb = (half[i] - po) / dd;
      double sa = -1, sb = 1;
      if (ta > tb) std::swap(ta, tb), std::swap(sa, sb);
      if (ta > t0) t0 = ta, a0 = i, s0 = sa;
      if (tb < t1) t1 = tb, a1 = i, s1 = sb;
    }
    if (t0 > t1) return std::nullopt;
    if (t0 > kEps) return Hit{t0, scale(s0, axis[a0])};
    if (t1 > kEps) return Hit{t1, scale(s1, axis[a1])};
    return std::nullopt;
  }
};

// A path's weight: the product of the reference model's weights, or 0 if it is stopped.
double trace(V3 o, V3 d, double eta, double alpha, const Slab *slab, bool correlated, Rng &rng) {
  double weight = 1;
  for (int bounce = 0; bounce < kMaxBounces; ++bounce) {
    std::optional<Hit> h = hit_unit_sphere(o, d);
    if (slab)
      if (const std::optional<Hit> s = slab->hit(o, d); s && (!h || s->t < h->t)) h = s;
    if (!h) return weight;  // the enclosure: radiance 1
    const V3 p = axpy(h->t, d, o), &n = h->normal;
    // Duff et al.'s (2017) orthonormal basis around n.
    const double sign = std::copysign(1.0, n[2]), a = -1 / (sign + n[2]), b = n[0] * n[1] * a;
    const V3 t{1 + sign * n[0] * n[0] * a, sign * b, -sign * n[0]}, bt{b, sign + n[1] * n[1] * a, -n[1]};
    const V3 wo{-dot3(d, t), -dot3(d, bt), -dot3(d, n)};
    const reference::Bounce s = reference::bounce(wo, eta, alpha, rng.next(), rng.next());
    const bool reflect = rng.next() < s.fresnel;
    const V3 &wl = reflect ? s.reflected : s.refracted;
    if (correlated)
      weight *= reflect ? s.w_reflect_correlated : s.w_refract_correlated;
    else
      weight *= reflect ? s.w_reflect : s.w_refract;
    if (weight == 0) return 0;
    d = unit(axpy(wl[0], t, axpy(wl[1], bt, scale(wl[2], n))));
    o = axpy(std::copysign(1e-6, wl[2]), n, p);
  }
  return 0;
}

std::vector<double> furnace_image(double eta, double alpha, bool slab, uint32_t width, uint32_t height,
                                  int paths, uint64_t seed, bool correlated) {
  const Slab box;
  Rng rng{seed};
  // The camera at (0, -3, 0) looks along +y, +z up and +x to the right, with a 40-degree field of view
  // across the width.
  const double half_width = std::tan(20 * kPi / 180), half_height = half_width * height / width;
  std::vector<double> image(size_t(width) * height);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      double sum = 0;
      for (int i = 0; i < paths; ++i) {
        const double sx = (2 * (x + rng.next()) / width - 1) * half_width;
        const double sy = (1 - 2 * (y + rng.next()) / height) * half_height;
        sum += trace({0, -3, 0}, unit({sx, 1, sy}), eta, alpha, slab ? &box : nullptr, correlated, rng);
      }
      image[size_t(y) * width + x] = sum / paths;
    }
  return image;
}

}  // namespace

std::vector<double> glass_furnace_lower_bound(double eta, double alpha, bool slab, uint32_t width,
                                              uint32_t height, int paths, uint64_t seed) {
  return furnace_image(eta, alpha, slab, width, height, paths, seed, false);
}

std::vector<double> glass_furnace_expected(double eta, double alpha, bool slab, uint32_t width,
                                           uint32_t height, int paths, uint64_t seed) {
  return furnace_image(eta, alpha, slab, width, height, paths, seed, true);
}

}  // namespace nimbus::extremes
