// The splat technique's camera passes; see photon_splats.hpp.
#include "photon_splats.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "light_path_trial.hpp"
#include "merging.hpp"
#include "useful_pixels.hpp"

namespace nimbus::caustics {
namespace {

// Splats per task: a map's visible photons share out evenly over the workers.
constexpr uint64_t kSplatsPerTask = 4096;

struct SplatJob {
  const SplatInputs *in;
  std::atomic<uint64_t> *clamped;
  std::vector<float> *light;    // per splat, the luminance it added (0: none)
  std::vector<float> *without;  // with a trial, what it would have added without light paths
};

// The weight of splat s of photon ph: the merge at x_1 it competes with is the one a camera path through
// the same pixel would look up with (the pixel's radius, the first lookup's probability, the time
// window around the photon's own time, since the path's camera time is the photon's); and the
// light-tracing technique, with the photon's density against its (light_paths.hpp).
// *without: the weight without light paths (light_path_trial.hpp), when asked for.
float weight(const MergeContext &mc, const PixelRadius &pixel_radius, size_t pixel, const PhotonSplat &s,
             const Photon &ph, bool &clamped, float *without = nullptr) {
  const MergeDensities d = first_merge_densities(mc, pixel_radius, pixel, s.length, ph.time_u);
  const Mis lt = mc.lt_paths > 0 ? mis(splat_eta(mc.lt_paths, s.density)) * std::exp2(Mis(ph.lt)) : 0.0;
  const Mis eta_splat = mis(splat_eta(double(mc.map_paths), s.density));
  if (without)
    *without = splat_weight(ph.A, ph.B, ph.b_valid(), s.w_cam, d.eta, d.neff, d.neff_b, eta_splat, clamped);
  return splat_weight(ph.A, ph.B, ph.b_valid(), s.w_cam, d.eta, d.neff, d.neff_b, eta_splat, clamped, lt);
}

void splat_range(const nimbus_thread_ctx_t *ctx, uint64_t begin, uint64_t end, void *user) {
  const SplatJob &job = *static_cast<const SplatJob *>(user);
  const SplatInputs &in = *job.in;
  const MergeContext &mc = *in.merge;
  const float inv_paths = 1.0f / float(mc.map_paths);
  uint64_t clamped = 0;
  for (uint64_t i = begin; i < end; ++i) {
    const PhotonSplat &s = in.splats[i];
    if (!(s.raster[0] >= 0 && s.raster[1] >= 0)) continue;
    const uint32_t x = uint32_t(s.raster[0]), y = uint32_t(s.raster[1]);
    if (x >= in.width || y >= in.height) continue;
    const Photon &ph = in.photons[s.photon];
    bool overflow = false;
    float w_without = 0;
    const float w = weight(mc, *in.pixel_radius, size_t(y) * in.width + x, s, ph, overflow,
                           job.without ? &w_without : nullptr);
    clamped += overflow ? 1 : 0;
    if (job.without) (*job.without)[i] = luminance(Rgb::load(s.value)) * (w_without * inv_paths);
    if (!(w > 0)) continue;
    float v[3];
    const Rgb value = Rgb::load(s.value) * (w * inv_paths);
    value.store(v);
    (*job.light)[i] = luminance(value);
    in.film->splat(in.host, ctx, NIMBUS_ELEMENT_BEAUTY, s.raster[0], s.raster[1], v);
    // Every splatted path has a merge technique: its light is the `caustics` element's (spec 8).
    if (mc.ids.diverted >= 0) in.film->splat(in.host, ctx, mc.ids.diverted, s.raster[0], s.raster[1], v);
    if (in.lightmix && mc.light_group && ph.light() < mc.light_group->size())
      in.lightmix->splat(in.host, ctx, (*mc.light_group)[ph.light()], s.raster[0], s.raster[1], v);
  }
  if (clamped) job.clamped->fetch_add(clamped, std::memory_order_relaxed);
}

}  // namespace

nimbus_status_t splat_photons(const SplatInputs &in, uint64_t &clamped) {
  if (in.splats.empty() || !in.merge || !(in.merge->map_paths > 0)) return NIMBUS_OK;
  std::atomic<uint64_t> overflows{0};
  std::vector<float> light(in.splats.size(), 0.0f), without(in.trial ? in.splats.size() : 0, 0.0f);
  SplatJob job{&in, &overflows, &light, in.trial ? &without : nullptr};
  const nimbus_status_t s =
      in.tasks->parallel_for(in.host, in.splats.size(), kSplatsPerTask, splat_range, &job);
  clamped += overflows.load();
  // In splat order, on this thread: the sums stay the same at any thread count.
  for (size_t i = 0; i < light.size(); ++i) {
    if (!(light[i] > 0) && !(in.trial && without[i] > 0)) continue;
    const PhotonSplat &sp = in.splats[i];
    const float split = in.photons[sp.photon].path & 1u ? -light[i] : light[i];  // as merging.cpp's halves
    const size_t pixel = size_t(sp.raster[1]) * in.width + size_t(sp.raster[0]);
    if (in.useful && light[i] > 0) in.useful->add_splat(pixel, light[i], split);
    if (in.trial) in.trial->add_splat(pixel, light[i], without[i]);
  }
  return s;
}

}  // namespace nimbus::caustics
