// Photon paths (solver spec section 4); see photon_tracer.hpp.
#include "photon_tracer.hpp"

#include <cstring>

#include <nimbus/cpp/rng.hpp>

#include "emission_strata.hpp"
#include "mis.hpp"
#include "sharpness.hpp"

namespace nimbus::caustics {
namespace {

// The emitter surface point a photon of area light `light` left from, as an interaction.
nimbus_interaction_t emission_point(uint32_t light, const nimbus_light_emission_t &es) {
  nimbus_interaction_t on_light{};
  std::memcpy(on_light.p, es.org, sizeof(on_light.p));
  std::memcpy(on_light.ng, es.n, sizeof(on_light.ng));
  std::memcpy(on_light.ns, es.n, sizeof(on_light.ns));
  on_light.light_id = light;
  on_light.flags = NIMBUS_IX_EMISSIVE;
  return on_light;
}

}  // namespace

// One photon path: emission by power-proportional light selection, storage at rough vertices after a
// sharp one, termination after two consecutive rough vertices (spec 4), MIS state per photon.
void PhotonTracer::trace(const nimbus_thread_ctx_t &ctx, uint64_t path, uint64_t paths, uint32_t pass,
                         PhotonChunk &out) const {
  nimbus_rng_t rng;
  svc_.rng->derive(h_, path, pass, kStreamPhoton, &rng);
  PhotonSamples samples(rng);
  trace(ctx, samples, path, paths, nullptr, out);
}

float PhotonTracer::trace(const nimbus_thread_ctx_t &ctx, PhotonSamples &samples, uint64_t path,
                          uint64_t paths, const ImportanceMap *importance, PhotonChunk &out) const {
  const nimbus_host_t *h = h_;
  float target = 0;
  float sel = 0;
  const uint32_t path_index = uint32_t(out.path_light.size());
  out.path_light.push_back(kNoLight);
  out.path_emission.push_back(kNoEmissionCell);
  const int64_t li = emitters_.pick(samples.next(), &sel);
  if (li < 0 || !(sel > 0)) return target;
  const uint32_t light = uint32_t(li);
  out.path_light[path_index] = light;
  const Emitter &em = emitters_[light];
  float ue[4] = {samples.next(), samples.next(), samples.next(), samples.next()};
  // The light's main pair of numbers (position for the sun, environment and area lights; direction
  // for point and spot lights) comes stratified along the pass (emission_strata.hpp).
  {
    const float xi = samples.next(), j0 = samples.next(), j1 = samples.next();
    if (samples.from_stream()) {
      const Vec2f s = emission_sample(path, paths, xi, j0, j1);
      const int first = em.infinite() || em.kind == EmitterKind::Area ? 0 : 2;
      ue[first] = s.x, ue[first + 1] = s.y;
    }
  }
  // A scene time from the shutter's curve when something moves (photon_windows.hpp): lookups compare its
  // number u, in which photons and camera paths are both uniform.
  const float time_u = scene_.timed ? samples.time_number() : 0.0f;
  const float time = scene_.time(h, time_u);
  nimbus_light_emission_t es;
  scene_.sample_emission(h, light, ue, time, es);
  if (!(es.pdf_pos > 0) || !(es.pdf_dir > 0)) return target;
  const bool delta_pos = es.flags & NIMBUS_LIGHT_DELTA_POSITION;
  const bool infinite = es.flags & NIMBUS_LIGHT_INFINITE;
  const Vec3f n_e = Vec3f::load(es.n);
  Vec3f dir0 = Vec3f::load(es.dir);
  Rgb Le = Rgb::load(es.Le);
  // The projection map (emitters.hpp) picks where the photon goes: a cone towards sharp geometry or the
  // light's own emission (finite lights), the targets' disk or the scene's (the sun).
  const float u_mix = samples.next();
  Vec3f org = Vec3f::load(es.org);
  float pdf_pos = es.pdf_pos, pdf_dir = es.pdf_dir;
  if (em.kind == EmitterKind::Environment) {
    // The bright parts of the map only (environment_emission.hpp), not the host's own sampling.
    const EnvironmentEmission::Sample s = emitters_.environment_sample(light, ue[2], ue[3], samples.next());
    if (!(s.pdf > 0)) return target;
    float w[3], L[3];
    s.dir.store(w);
    svc_.lights->eval_infinite(h, light, w, L);
    dir0 = -s.dir, Le = Rgb::load(L), pdf_dir = s.pdf;
  }
  if (infinite) {
    org = emitters_.emission_origin(light, dir0, u_mix, ue[0], ue[1], &out.path_emission[path_index]);
    pdf_pos = emitters_.sun_pdf_pos(light, org, dir0);
  } else {
    dir0 = emitters_.sample_direction(light, org, u_mix, ue[2], ue[3], dir0, &out.path_emission[path_index]);
    pdf_dir = emitters_.finite_pdf_dir(light, org, n_e, dir0, time);
    if (dir0 != Vec3f::load(es.dir)) Le = emitted(light, es, dir0, time);
  }
  const float cos_e = delta_pos || infinite ? 1.0f : std::abs(dot(n_e, dir0));
  const float lp = sel * pdf_pos * pdf_dir;
  Rgb beta = Le * (cos_e / lp);
  if (is_black(beta) || !is_finite(beta)) return target;
  PhotonMis mis_state;
  mis_state.emit(em.hittable(), cos_e, lp);
  const float lt_ratio =
      lt_ ? density_ratio_log2(lt_->lp(emitters_, light, org, n_e, dir0, time), lp) : -kInfinity;
  // RGB until a dispersive vertex, then one wavelength and the scalar power at it (spec 7.2).
  sdk::PathSpectrum spectrum(h, spectral_, svc_.bsdf);

  nimbus_ray_t ray = sdk::emission_ray(org, dir0, es.flags);

  bool had_sharp = false, prev_rough = false;
  for (uint32_t depth = 1; depth <= kPhotonMaxVertices; ++depth) {
    LightSideVertex v;
    if (!arrive(ctx, ray, time, mis_state, v, out.work, kRayWork)) return target;
    const nimbus_interaction_t &ix = v.ix;
    spectrum.disperse(
        v.lobes, [&] { return samples.next(); }, beta, false);
    // A photon path that missed every sharp surface ends at its first vertex (see CameraMis: merges
    // need a sharp first photon vertex). Its only photons would come after a rough-sharp-rough
    // sequence, which path tracing samples with NEE at that first vertex, as for directions outside
    // the emission target; tracing them on would cost a large share of the photon vertices.
    if (v.rough && depth == 1) return target;
    Mis nee_term = 0;
    if (depth == 1 && !v.smooth_only) nee_term = first_vertex_nee(ix, light, em, es, v.wo, lp, v.c_in);

    // Store after a sharp bounce; a photon of depth d completes paths of >= d + 1 segments.
    const bool stored = v.rough && had_sharp && depth + 1 <= max_depth_;
    float vertex_importance = 0;
    if (stored) {
      if (importance) vertex_importance = importance->at(Vec3f::load(ix.p));
      target = std::max(target, vertex_importance);
      Photon ph;
      std::memcpy(ph.p, ix.p, sizeof(ph.p));
      ph.dir = encode_octahedral(v.wo);
      ph.normal = encode_octahedral(v.ng);
      beta.store(ph.power);
      ph.A = mis_state.log2_A();
      ph.B = mis_state.log2_B();
      ph.B_importance = mis_state.log2_B_importance();
      ph.B_importance2 = mis_state.log2_B_importance2();
      ph.bits = Photon::pack(depth, prev_rough, mis_state.b_valid, light);
      ph.path = path_index;
      ph.time_u = time_u;
      ph.lambda = spectrum.lambda();
      ph.lt = lt_ratio;
      out.photons.push_back(ph);
      out.work += kPhotonWork;
      if (splat_.enabled) connect_to_lens(ctx, ix, v.wo, beta, time, hash_keys({path, depth}), out);
    }
    if (v.rough && prev_rough) return target;  // two consecutive rough vertices
    if (depth == kPhotonMaxVertices) return target;

    const float u[3] = {samples.next(), samples.next(), samples.next()};
    if (!scatter(
            v, spectrum, u, [&] { return samples.next(); }, stored, nee_term, vertex_importance, mis_state,
            beta, ray))
      return target;
    prev_rough = v.rough;
    had_sharp = had_sharp || !v.rough;
  }
  return target;
}

bool PhotonTracer::arrive(const nimbus_thread_ctx_t &ctx, const nimbus_ray_t &ray, float time, PhotonMis &mis,
                          LightSideVertex &v, uint64_t &work, uint64_t ray_work) const {
  nimbus_hit_t hit;
  scene_.trace(h_, ctx, ray, time, hit, v.ix);
  work += ray_work;
  if (hit.geom_id == NIMBUS_NONE) return false;
  v.wo = -Vec3f::load(ray.dir), v.ng = Vec3f::load(v.ix.ng);
  v.c_in = std::abs(dot(v.ng, v.wo));
  if (!(v.c_in > 0)) return false;
  mis.arrive(v.c_in);
  v.lobes = svc_.bsdf->lobes(h_, &v.ix);
  v.rough = !is_sharp(svc_.bsdf, h_, v.ix, v.lobes);
  v.smooth_only = !has(v.lobes, NIMBUS_LOBE_DIFFUSE | NIMBUS_LOBE_GLOSSY);
  return true;
}

// The splat of the photon just stored at ix (photon_splats.hpp): its light towards the lens, as a light
// tracer connects it, if the lens sees it. key picks the lens point (a hash: the photon path's own
// numbers stay as they are). Reflection only: a merge needs the photon on the camera's side of the
// surface (merging.cpp's side test), and the splat shares its paths.
void PhotonTracer::connect_to_lens(const nimbus_thread_ctx_t &ctx, const nimbus_interaction_t &ix,
                                   const Vec3f &wo, const Rgb &beta, float time, uint64_t key,
                                   PhotonChunk &out) const {
  const uint64_t u = hash_keys({key, 0x6c656e73});
  const float lens_u[2] = {float(u >> 40) * 0x1p-24f, float((u >> 16) & 0xffffffu) * 0x1p-24f};
  LensLink link;
  if (!link_to_lens(ctx, ix, wo, beta, lens_u, time, true, splat_.axis, splat_.theta_pix, link, out.work,
                    kRayWork))
    return;
  PhotonSplat s;
  s.raster[0] = link.raster[0], s.raster[1] = link.raster[1];
  link.value.store(s.value);
  s.w_cam = link.w_cam;
  s.density = float(link.density);
  s.length = link.length;
  s.photon = uint32_t(out.photons.size() - 1);
  if (s.density > 0 && std::isfinite(s.density)) out.splats.push_back(s);
}

// The light tracer's connection of vertex ix to the lens point lens_u picks: its value (importance
// transport), the camera path's pdf of the vertex's incoming direction (as a merge evaluates it), and
// the camera paths' density of first vertices there. False when the lens does not see it, or (with
// reflection_only) sees its other side. Its visibility ray adds ray_work to work.
bool PhotonTracer::link_to_lens(const nimbus_thread_ctx_t &ctx, const nimbus_interaction_t &ix,
                                const Vec3f &wo, const Rgb &beta, const float lens_u[2], float time,
                                bool reflection_only, const Vec3f &axis, float theta_pix, LensLink &link,
                                uint64_t &work, uint64_t ray_work) const {
  float lens[3];
  const float we = scene_.connect(h_, ix.p, time, lens_u, link.raster, lens);
  if (!(we > 0)) return false;
  const Vec3f p = Vec3f::load(ix.p), ng = Vec3f::load(ix.ng), to_lens = Vec3f::load(lens) - p;
  link.length = length(to_lens);
  if (!(link.length > 0)) return false;
  const Vec3f wc = to_lens / link.length;
  link.same_side = dot(ng, wc) * dot(ng, wo) > 0;
  if (reflection_only && !link.same_side) return false;
  float wo_arr[3], wc_arr[3], f[3], f_cam[3];
  wo.store(wo_arr), wc.store(wc_arr);
  link.w_cam = 0;
  svc_.bsdf->eval(h_, &ix, wo_arr, wc_arr, NIMBUS_MODE_IMPORTANCE, f, nullptr, nullptr);
  svc_.bsdf->eval(h_, &ix, wc_arr, wo_arr, NIMBUS_MODE_RADIANCE, f_cam, &link.w_cam, nullptr);
  link.value = beta * Rgb::load(f) * (std::abs(dot(Vec3f::load(ix.ns), wc)) * we);
  if (is_black(link.value) || !is_finite(link.value) || !(link.w_cam > 0)) return false;
  link.density = camera_density(link.length, dot(ng, wc), dot(axis, -wc), theta_pix);
  if (!(link.density > 0) || !std::isfinite(link.density)) return false;
  work += ray_work;
  return !scene_.occluded_to(h_, ctx, ix, lens, false, time);
}

// Radiance (area) or intensity (point, spot) that finite light `light` emits from es.org along w.
Rgb PhotonTracer::emitted(uint32_t light, const nimbus_light_emission_t &es, const Vec3f &w,
                          float time) const {
  float wo[3], Le[3];
  w.store(wo);
  scene_.eval_emission(h_, light, es.org, es.n, wo, time, Le);
  return Rgb::load(Le);
}

// E of the first photon vertex: how NEE from it would have sampled the emission point.
Mis PhotonTracer::first_vertex_nee(const nimbus_interaction_t &ix, uint32_t light, const Emitter &em,
                                   const nimbus_light_emission_t &es, const Vec3f &wo, float lp,
                                   float c_in) const {
  const nimbus_host_t *h = h_;
  const float pmf = selection_.pmf(&ix, light);
  if (!(pmf > 0)) return 0;
  float wo_arr[3];
  wo.store(wo_arr);
  if (em.delta_position()) {
    const float d2 = length_squared(Vec3f::load(es.org) - Vec3f::load(ix.p));  // point and spot
    return photon_nee_term(true, pmf, d2, lp, c_in);
  }
  if (em.infinite()) {
    const float pdf = em.delta_direction() ? 1.0f : svc_.lights->pdf_incident(h, light, &ix, wo_arr, nullptr);
    return photon_nee_term(true, pmf * pdf, 1.0f, lp, c_in);
  }
  const nimbus_interaction_t on_light = emission_point(light, es);
  const float pdf = svc_.lights->pdf_incident(h, light, &ix, wo_arr, &on_light);
  const float cos_z = std::abs(dot(Vec3f::load(es.n), wo));  // wo = -(the photon's direction)
  // nk * d2 = pmf * pdf * cos_z: pass d2 = 1 with nk already multiplied out.
  return photon_nee_term(true, pmf * pdf * cos_z, 1.0f, lp, c_in);
}

}  // namespace nimbus::caustics
