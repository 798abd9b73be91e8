// The light-tracing technique's paths; see light_paths.hpp.
#include "light_paths.hpp"

#include <cmath>

#include <nimbus/cpp/rng.hpp>

#include "merging.hpp"
#include "photon_tracer.hpp"
#include "sharpness.hpp"

namespace nimbus::caustics {
namespace {

// Light paths per task.
constexpr uint64_t kLightPathsPerTask = 1024;

}  // namespace

nimbus_status_t trace_light_paths(const PhotonTracer &tracer, const nimbus_host_tasks_v1_t *tasks,
                                  const nimbus_host_t *h, const LightTracing &in, LightTally &tally) {
  const uint64_t paths = uint64_t(in.merge->lt_paths);
  struct Job {
    const PhotonTracer *tracer;
    const LightTracing *in;
    std::vector<LightTally> tallies;  // one per task: counts and light sum in task order
  } job{&tracer, &in, std::vector<LightTally>((paths + kLightPathsPerTask - 1) / kLightPathsPerTask)};
  const auto fn = [](const nimbus_thread_ctx_t *ctx, uint64_t b, uint64_t e, void *user) {
    Job &j = *static_cast<Job *>(user);
    LightTally &t = j.tallies[b / kLightPathsPerTask];
    for (uint64_t p = b; p < e; ++p) j.tracer->trace_light(*ctx, p, *j.in, t);
  };
  const nimbus_status_t s = tasks->parallel_for(h, paths, kLightPathsPerTask, fn, &job);
  for (const LightTally &t : job.tallies) {
    tally.work += t.work, tally.splats += t.splats, tally.clamped += t.clamped;
    tally.light.insert(tally.light.end(), t.light.begin(), t.light.end());
  }
  return s;
}

// One light path: the light by power, the host's emission, the photon tracer's bounces and Russian
// roulette, and at every rough vertex after the first bounce that can complete a path of at most
// max_depth segments, one connection to the lens. PhotonMis follows the path with lp_lt; `stored` and `alive`
// replay the photon tracer's rules (photon_tracer.cpp) so that the weights count the merges and splats the
// path has.
void PhotonTracer::trace_light(const nimbus_thread_ctx_t &ctx, uint64_t path, const LightTracing &in,
                               LightTally &out) const {
  const nimbus_host_t *h = h_;
  const MergeContext &mc = *in.merge;
  nimbus_rng_t rng;
  svc_.rng->derive(h, path, in.iteration, kStreamLightPath, &rng);
  float sel = 0;
  const int64_t li = mc.lt_emission->pick(next_uniform(rng), &sel);
  if (li < 0 || !(sel > 0)) return;
  const uint32_t light = uint32_t(li);
  const Emitter &em = emitters_[light];
  // A scene time when something moves, drawn from the shutter's curve as photons and camera paths draw
  // theirs (photon_windows.hpp): the path's merges would take photons of a window around it.
  const float time_u = scene_.timed ? next_uniform(rng) : 0.0f;
  const float time = scene_.time(h, time_u);
  const float ue[4] = {next_uniform(rng), next_uniform(rng), next_uniform(rng), next_uniform(rng)};
  nimbus_light_emission_t es;
  scene_.sample_emission(h, light, ue, time, es);
  if (!(es.pdf_pos > 0) || !(es.pdf_dir > 0) || (es.flags & NIMBUS_LIGHT_INFINITE)) return;
  const bool delta_pos = es.flags & NIMBUS_LIGHT_DELTA_POSITION;
  const Vec3f org = Vec3f::load(es.org), n_e = Vec3f::load(es.n), dir0 = Vec3f::load(es.dir);
  const float cos_e = delta_pos ? 1.0f : std::abs(dot(n_e, dir0));
  const float lp = mc.lt_emission->lp(emitters_, light, org, n_e, dir0, time);
  Rgb beta = Rgb::load(es.Le) * (cos_e / (sel * (delta_pos ? 1.0f : es.pdf_pos) * es.pdf_dir));
  if (!(lp > 0) || is_black(beta) || !is_finite(beta)) return;
  PhotonMis state;
  state.emit(em.hittable(), cos_e, lp);
  LightVertexClass c;
  c.light = light;
  c.time = time, c.time_u = time_u;
  c.rho = std::exp2(Mis(density_ratio_log2(emitters_.lp(light, org, n_e, dir0, org, time), lp)));

  nimbus_ray_t ray = sdk::emission_ray(org, dir0, es.flags);
  const sdk::PathSpectrum rgb(h, nullptr, svc_.bsdf);        // light paths are off where light disperses
  bool had_sharp = false, prev_rough = false, alive = true;  // alive: a photon path would go on
  for (uint32_t depth = 1; depth < max_depth_; ++depth) {
    LightSideVertex v;
    if (!arrive(ctx, ray, time, state, v, out.work, kLightPathRayWork)) return;
    const Mis nee_term =
        depth == 1 && !v.smooth_only ? first_vertex_nee(v.ix, light, em, es, v.wo, lp, v.c_in) : 0.0;
    c.depth = depth;
    c.stored = alive && v.rough && had_sharp && depth <= kPhotonMaxVertices;
    if (v.rough && !v.smooth_only && depth >= 2) {
      const float lens_u[2] = {next_uniform(rng), next_uniform(rng)};
      connect_light_vertex(ctx, v.ix, v.wo, beta, state, c, lens_u, in, out);
    }
    if (v.rough && (depth == 1 || prev_rough)) alive = false;
    if (depth + 1 >= max_depth_) return;  // the next vertex would complete more than max_depth segments

    const float u[3] = {next_uniform(rng), next_uniform(rng), next_uniform(rng)};
    if (!scatter(
            v, rgb, u, [&] { return next_uniform(rng); }, c.stored, nee_term, 0.0f, state, beta, ray))
      return;
    prev_rough = v.rough;
    had_sharp = had_sharp || !v.rough;
  }
}

// The connection of rough vertex ix to the lens: its light towards the lens times its weight, into
// beauty and the path's lighting element and LightMix group.
void PhotonTracer::connect_light_vertex(const nimbus_thread_ctx_t &ctx, const nimbus_interaction_t &ix,
                                        const Vec3f &wo, const Rgb &beta, const PhotonMis &state,
                                        const LightVertexClass &c, const float lens_u[2],
                                        const LightTracing &in, LightTally &out) const {
  const MergeContext &mc = *in.merge;
  LensLink link;
  if (!link_to_lens(ctx, ix, wo, beta, lens_u, c.time, false, mc.view_axis, mc.theta_pix, link, out.work,
                    kLightPathRayWork))
    return;
  const float *raster = link.raster;
  if (!(raster[0] >= 0 && raster[1] >= 0)) return;
  const uint32_t x = uint32_t(raster[0]), y = uint32_t(raster[1]);
  if (x >= in.width || y >= in.height) return;
  // A merge at x_1 needs the photon on the camera's side of the surface (merging.cpp's side test).
  const bool v1 = c.stored && link.same_side;
  const MergeDensities md =
      first_merge_densities(mc, *in.pixel_radius, size_t(y) * in.width + x, link.length, c.time_u);
  const double density = link.density;
  const Mis eta_splat = v1 && mc.splat_paths > 0 ? mis(splat_eta(mc.splat_paths, density)) : 0.0;
  bool clamped = false;
  const float w = lt_weight(state.log2_A(), state.log2_B(), state.b_valid, v1, link.w_cam, md.eta, md.neff,
                            md.neff_b, eta_splat, c.rho, mis(splat_eta(mc.lt_paths, density)), clamped);
  out.clamped += clamped ? 1 : 0;
  if (!(w > 0)) return;
  float v[3];
  (link.value * float(w / mc.lt_paths)).store(v);
  in.film->splat(h_, &ctx, NIMBUS_ELEMENT_BEAUTY, raster[0], raster[1], v);
  ++out.splats;
  if (in.record_light) out.light.push_back({y * in.width + x, luminance(Rgb::load(v))});
  // The path's lighting element, as the camera side sorts the same path (spec 8).
  const bool caustic = c.rho > 0 && (v1 || state.b_valid);
  const nimbus_element_t el = caustic ? mc.ids.diverted : mc.ids.indirect;
  if (mc.ids.split_light && el >= 0) in.film->splat(h_, &ctx, el, raster[0], raster[1], v);
  if (in.lightmix && mc.light_group && c.light < mc.light_group->size())
    in.lightmix->splat(h_, &ctx, (*mc.light_group)[c.light], raster[0], raster[1], v);
}

}  // namespace nimbus::caustics
