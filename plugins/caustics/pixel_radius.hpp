// A merge radius per pixel from the photon density its lookups found. The schedule's radius
// (schedule.hpp) is one size for the image; where photons crowd, as at the focus of a point light behind
// glass, a kernel of that size spreads the bright focus onto its dark surroundings, a bias that only
// time shrinks. Here each pixel's first lookups measure the density of photons around it, and the pixel's
// radius shrinks until its kernel would hold about kTargetPhotons of them (never below kMinScale of the
// schedule's): sharp where photons are dense, which is where a smaller kernel costs the least variance.
// The scale depends only on earlier iterations, so it is fixed during a camera pass and every technique
// of one path sees the same radius (MIS stays a partition of unity); the render stays deterministic at
// any thread count, and the sums are saved for a resumed render.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "useful_pixels.hpp"

namespace nimbus::caustics {

// Photons a pixel's kernel should hold per lookup before it shrinks below the schedule's radius. Few: at a
// focus's edge the kernel's blur costs more than the photon noise a small kernel adds inside a smooth
// caustic (4 against 8 and 16 at equal time: docs/performance.md section 5).
inline constexpr double kTargetPhotons = 4;
// The smallest radius, relative to the schedule's.
inline constexpr float kMinScale = 0.25f;

class PixelRadius {
 public:
  // [main-thread] Forgets every pixel's density; `pixels` entries (0 when the solver is not armed).
  void reset(size_t pixels) {
    sums_.assign(pixels, Sums{});
    density_.assign(pixels, 0.0f);
  }

  // [render-thread] The radius of pixel i's camera path whose schedule radius is r, with `neff` effective
  // photon paths at its first lookup vertex. Reads only what end_iteration() froze.
  float radius(size_t i, float r, float neff) const {
    if (i >= density_.size() || !(density_[i] > 0)) return r;
    const double expected = density_[i] * M_PI * double(r) * r * neff;  // photons in the schedule's kernel
    if (!(expected > kTargetPhotons)) return r;
    return r * std::max(kMinScale, float(std::sqrt(kTargetPhotons / expected)));
  }

  // [render-thread] Starts fetching what radius() and found() will read of pixel i.
  void prefetch(size_t i) const {
    if (i < sums_.size()) __builtin_prefetch(&sums_[i], 1), __builtin_prefetch(&density_[i], 0);
  }

  // [render-thread] A first lookup of pixel i found `found` photons within radius r (each counted by its
  // light's density weight, merging.hpp), with `neff` effective photon paths (each pixel belongs to one
  // tile, so no two threads meet).
  void found(size_t i, double found, float r, float neff) {
    if (i >= sums_.size()) return;
    sums_[i].photons += found;
    sums_[i].area += M_PI * double(r) * r * neff;
  }

  // [main-thread] After a camera pass: the densities the next pass reads, over a recent window (the
  // photon emission adapts, so old maps say less about the next one).
  void end_iteration() {
    for (size_t i = 0; i < sums_.size(); ++i) {
      Sums &s = sums_[i];
      density_[i] = s.area > 0 ? float(s.photons / s.area) : 0.0f;
      s.photons *= kWindowDecay, s.area *= kWindowDecay;
    }
  }

  // [main-thread] The sums and the densities they gave, for a resumed render; restore changes nothing
  // unless it reads exactly this many pixels.
  template <class Writer>
  void save(Writer &w) const {
    w.put_array(std::span<const Sums>(sums_));
    w.put_array(std::span<const float>(density_));
  }
  template <class Reader>
  bool restore(Reader &r) {
    std::vector<Sums> sums;
    std::vector<float> density;
    if (!r.get_array(sums, sums_.size()) || !r.get_array(density, density_.size())) return false;
    for (const float d : density)
      if (!(d >= 0) || !std::isfinite(d)) return false;
    sums_ = std::move(sums), density_ = std::move(density);
    return true;
  }

 private:
  struct Sums {
    double photons = 0;  // photons the pixel's first lookups found (decayed window)
    double area = 0;     // sum of pi r^2 neff over those lookups
  };
  std::vector<Sums> sums_;
  std::vector<float> density_;  // photons per unit area per effective photon path, frozen for a pass
};

}  // namespace nimbus::caustics
