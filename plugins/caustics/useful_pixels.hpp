// Per-pixel statistics of the camera samples (solver spec section 5), over a recent window: each
// iteration's end scales the sums by kWindowDecay, so they follow the current photon map rather than the
// render's history. From them: the useful pixels (Mp > tau Tp, Mp the MIS-weighted merge light and Tp
// the beauty), and the relative variance one iteration leaves in the image, split into the part that
// more photons reduce (the budget's V_m) and the rest (V_c). A map serves at least two iterations, so
// each pixel has two or more samples under one map: their spread is the merges' camera-side variance
// (which only camera samples reduce), and the spread of the per-map means beyond it is the photon noise.
// Half the squared difference of consecutive maps' means estimates Var(mean) = V_photon + V_within / n.
// Until a pixel has seen two maps, a map whose paths are independent (unguided passes: the probe, and
// every pass without a guide) estimates its own photon noise from its two halves, the photons of
// even-numbered and odd-numbered paths: given the camera samples, the merge mean is the sum of the two
// halves' independent estimates, whose difference has the same variance. So the budget measures from
// the first map on, rather than pricing a second blind pass.
// Each class of lookup's second moment (lookup_roulette.hpp) is kept on the same window and weights.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <nimbus/cpp/math.hpp>
#include <nimbus/cpp/tasks.hpp>

#include "lookup_roulette.hpp"
#include "schedule.hpp"

namespace nimbus::caustics {

// Weight of the previous iterations' sums after each iteration: a window of about 8 iterations.
inline constexpr float kWindowDecay = 0.875f;
// The relMSE's offset (relMSE = (I - R)^2 / (R^2 + 0.01)): variances are weighted as that error weighs
// them.
inline constexpr double kRelativeOffset = 0.01;

class UsefulPixels {
 public:
  struct Summary {
    double useful = 0;    // share of the rendered pixels with Mp > kIdleThreshold Tp
    double v_merge = 0;   // mean over pixels of var(merge part) / (Tp^2 + offset), per iteration
    double v_camera = 0;  // the same for the rest of the sample (beauty minus merges)
    // per class of lookup, the mean over pixels of the lookups' second moment at q = 1 / (Tp^2 + offset)
    std::array<double, kLookupClasses> second_moment{};
  };

  // [main-thread] Zeroes the sums of a width x height image (0: none kept).
  void reset(size_t pixels) { sums_.assign(pixels, Sums{}), halves_independent_ = false; }

  // [main-thread] Every pixel's sums, for a resumed render; restore changes nothing unless it reads the
  // sums of exactly this many pixels.
  template <class Writer>
  void save(Writer &w) const {
    w.put_array(std::span<const Sums>(sums_)), w.put(uint8_t(halves_independent_));
  }
  template <class Reader>
  bool restore(Reader &r) {
    std::vector<Sums> sums;
    uint8_t halves = 0;
    if (!r.get_array(sums, sums_.size()) || !r.get(halves)) return false;
    sums_ = std::move(sums), halves_independent_ = halves != 0;
    return true;
  }

  // [render-thread] One sample of pixel i (each pixel belongs to one tile, so no two threads meet);
  // moment: per class of lookup, the sum over its lookups of q Y^2 (Y the luminance a lookup added);
  // split: luminance of the merges of even-numbered photon paths minus odd-numbered ones.
  // Light splatted into the pixel this iteration (add_splat) counts as part of this sample's merged light:
  // the photons' light is the merges' and the splats' together, whose sum does not depend on how MIS
  // shares it between them (a share that changes from map to map).
  void add(size_t i, const Rgb &beauty, const Rgb &merged, const std::array<float, kLookupClasses> &moment,
           float split = 0) {
    Sums &s = sums_[i];
    const float b = luminance(beauty) + s.splat, m = luminance(merged) + s.splat, c = b - m;
    split += s.splat_split;
    s.splat = 0, s.splat_split = 0;
    s.n += 1, s.total += b, s.merge += m, s.camera2 += c * c;
    for (uint32_t k = 0; k < kLookupClasses; ++k) s.moment[k] += moment[k];
    s.map_n += 1, s.map_merge += m, s.map_merge2 += m * m, s.map_split += split;
  }
  // [render-thread] Starts fetching pixel i's sums, which add() will read.
  void prefetch(size_t i) const {
    if (i < sums_.size()) __builtin_prefetch(&sums_[i], 1);
  }
  // [render-thread] The same from a sample record (caustics_record.hpp).
  template <class Record>
  void add(size_t i, const Record &r) {
    add(i, r.beauty, r.merge, r.lookup_moment, r.merge_split);
  }

  // [main-thread] Light (luminance) splatted into pixel i before this iteration's camera pass
  // (photon_splats.hpp), and its share from even-numbered photon paths minus odd-numbered ones.
  void add_splat(size_t i, float light, float split) {
    sums_[i].splat += light, sums_[i].splat_split += split;
  }

  // [main-thread] A new photon map replaces the current one: each pixel's merge mean under the old map
  // is compared with the one before it. halves_independent: the new map's paths are independent (an
  // unguided pass), so its halves measure its photon noise.
  void map_changed(bool halves_independent = false, const sdk::ParallelFor &parallel = sdk::serial_for) {
    halves_independent_ = halves_independent;
    sdk::parallel_ranges(parallel, sums_.size(), kChunk, [&](size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) {
        Sums &s = sums_[i];
        if (!(s.map_n > 1)) {
          s.map_n = 0, s.map_merge = 0, s.map_merge2 = 0, s.map_split = 0;
          continue;
        }
        const float mean = s.map_merge / s.map_n;
        const float within = std::max(0.0f, (s.map_merge2 - s.map_merge * mean) / (s.map_n - 1));
        if (s.has_previous) {
          // Var(mean) = V_photon + V_within / n: the photon part is what is left.
          const float d = std::max(0.0f, 0.5f * (mean - s.previous) * (mean - s.previous) - within / s.map_n);
          s.between = s.has_between ? kWindowDecay * s.between + (1 - kWindowDecay) * d : d;
          s.within = s.has_between ? kWindowDecay * s.within + (1 - kWindowDecay) * within : within;
          s.has_between = 1;
        }
        s.previous = mean, s.has_previous = 1;
        s.map_n = 0, s.map_merge = 0, s.map_merge2 = 0, s.map_split = 0;
      }
    });
  }

  // [main-thread] The summary over the `pixels` rendered pixels (pixels outside the render region have
  // no samples and never count), for maps that each serve `iterations_per_map` iterations; then the
  // window moves on. Chunks of pixels are summed concurrently and combined in their order, so the
  // summary does not depend on the thread count.
  Summary summarize(uint64_t pixels, double iterations_per_map,
                    const sdk::ParallelFor &parallel = sdk::serial_for) {
    const size_t chunks = (sums_.size() + kChunk - 1) / kChunk;
    std::vector<Partial> parts(chunks);
    sdk::parallel_ranges(parallel, sums_.size(), kChunk, [&](size_t begin, size_t end) {
      parts[begin / kChunk] = summarize_range(begin, end, iterations_per_map);
    });
    Partial all;
    for (const Partial &p : parts) all += p;
    Summary out;
    out.v_merge = all.v_merge, out.v_camera = all.v_camera, out.second_moment = all.second_moment;
    if (pixels > 0) {
      out.useful = std::min(1.0, double(all.useful) / double(pixels));
      out.v_merge /= double(pixels), out.v_camera /= double(pixels);
      for (double &m : out.second_moment) m /= double(pixels);
      // One sample has no spread: the merges' variance is unmeasured until the window holds two per
      // pixel (one of them decayed), which the split of a map's halves would otherwise price alone.
      if (all.samples < 1.5 * double(pixels)) out.v_merge = 0;
    }
    return out;
  }

 private:
  static constexpr size_t kChunk = 16384;  // pixels per task of summarize
  // One chunk's sums: the summary's before the division by the pixel count.
  struct Partial {
    uint64_t useful = 0;
    double samples = 0;  // the window's (decayed) sample counts
    double v_merge = 0, v_camera = 0;
    std::array<double, kLookupClasses> second_moment{};
    Partial &operator+=(const Partial &o) {
      useful += o.useful, samples += o.samples, v_merge += o.v_merge, v_camera += o.v_camera;
      for (uint32_t k = 0; k < kLookupClasses; ++k) second_moment[k] += o.second_moment[k];
      return *this;
    }
  };

  Partial summarize_range(size_t begin, size_t end, double iterations_per_map) {
    Partial out;
    for (size_t i = begin; i < end; ++i) {
      Sums &s = sums_[i];
      if (s.n > 0) {
        out.samples += s.n;
        out.useful += s.merge > float(kIdleThreshold) * s.total ? 1 : 0;
        const double n = s.n, mean_t = s.total / n, mean_c = mean_t - s.merge / n;
        const double weight = 1 / (mean_t * mean_t + kRelativeOffset);
        // A map's photon noise is shared by the k iterations it serves: k times that of one iteration's
        // own map. The merges' camera-side variance counts with the rest (camera samples reduce it).
        if (s.has_between) {
          out.v_merge += double(s.between) * iterations_per_map * weight;
        } else if (halves_independent_ && s.map_n > 0) {
          const double half_difference = s.map_split / s.map_n;
          out.v_merge += half_difference * half_difference * iterations_per_map * weight;
        }
        out.v_camera += (std::max(0.0, s.camera2 / n - mean_c * mean_c) + double(s.within)) * weight;
        for (uint32_t k = 0; k < kLookupClasses; ++k) out.second_moment[k] += s.moment[k] / n * weight;
      }
      s.n *= kWindowDecay, s.total *= kWindowDecay, s.merge *= kWindowDecay, s.camera2 *= kWindowDecay;
      for (float &m : s.moment) m *= kWindowDecay;
    }
    return out;
  }

  // No padding bytes (the flags' are explicit), so that a saved state is the same bytes every time.
  struct Sums {
    float n = 0, total = 0, merge = 0, camera2 = 0;  // the window's samples
    float splat = 0, splat_split = 0;                // splatted light awaiting this iteration's sample
    float moment[kLookupClasses] = {0, 0};           // the window's lookup second moments
    float map_n = 0, map_merge = 0, map_merge2 = 0;  // the current map's samples
    float map_split = 0;                             // and their merges' half difference (see the top)
    float previous = 0;                              // the previous map's merge mean
    float between = 0, within = 0;                   // photon variance of a map; merges' sample variance
    uint8_t has_previous = 0, has_between = 0, unused[2] = {0, 0};
  };
  static_assert(sizeof(Sums) == (14 + kLookupClasses) * sizeof(float));
  std::vector<Sums> sums_;
  bool halves_independent_ = false;  // the current map's (see map_changed)
};

}  // namespace nimbus::caustics
