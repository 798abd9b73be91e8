// Photon lookups of the camera side; see merging.hpp.
#include "merging.hpp"

namespace nimbus::caustics {
namespace {

// What a photon of wavelength lambda_p (0: RGB) with `power` brings to a camera path of wavelength
// lambda_c (0: RGB), as the camera path's colour state reads it (spec 7.2): an RGB photon uplifted at
// lambda_c; a photon's value at lambda_p weighed by that wavelength's colour for an RGB camera path; for
// two wavelengths, the photon only within the lookup's window around lambda_c, times the window's kernel.
// False when the photon brings nothing.
bool photon_at_wavelength(const MergeContext &mc, float lambda_p, float lambda_c,
                          const MirroredWindow &window, Rgb &power) {
  if (lambda_c > 0 && lambda_p > 0) {
    power = power * window.weight(lambda_p);
  } else if (lambda_c > 0) {
    float rgb[3];
    power.store(rgb);
    power = Rgb(mc.spectral->uplift(mc.host, rgb, lambda_c));
  } else if (lambda_p > 0) {
    power = spectral_rgb_weight(lambda_p) * power.x;
  }
  return !is_black(power);
}

}  // namespace

LookupCost merge_photons(const MergeContext &mc, const nimbus_interaction_t &ix, const Vec3f &wo,
                         const Rgb &beta, const CameraMis &mis_state, float r, uint32_t s,
                         uint32_t rough_count, float neff, const TimeWindow &window, float lambda,
                         Mis eta_splat, CausticsRecord &rec) {
  const float q = mc.lookup_probability[lookup_class(rough_count)];
  uint32_t evaluated = 0;
  float density_count = 0;
  const float r2 = r * r;
  // The photons' power is relative to a uniform path's (guided_pass.cpp), so 1 / N_u normalises it.
  const float inv_paths = 1.0f / (float(mc.map_paths) * q);
  // The merges at the photon's rough vertices (B) are lookups after the camera path's first rough vertex.
  // B carries each of its vertices' effective counts relative to N_u (guided_pass.cpp).
  const MergeDensities d = merge_densities(mc, r, neff, rough_count, window.rho);
  const Mis m_neff = d.neff, eta = d.eta, m_neff_b = d.neff_b;
  const Vec3f ng = Vec3f::load(ix.ng);
  float wo_arr[3];
  wo.store(wo_arr);
  const float kernel_norm = 2 / (kPi * r2);
  const MirroredWindow lambda_window = PhotonClock::lambda_window(lambda, mc.lambda_half_width);
  // Photons on the same flat surface carry the same quantised normal: skip decoding those. Encoded at
  // the first photon found: most lookups find none (query() turns them away first).
  uint32_t ng_code = 0;
  bool ng_encoded = false;
  Rgb sum(0);          // the lookup's light (without LightMix, one record entry per lookup)
  Rgb split(0);        // the same from even-numbered photon paths minus odd-numbered ones
  Rgb sum_without(0);  // the lookup's light without light paths
  const uint32_t leaves = mc.map->query(Vec3f::load(ix.p), r, [&](const PhotonData &ph, float d2) {
    const uint32_t k = s + ph.depth();
    if (k > mc.max_depth) return;
    const float in_time = window.active ? window.weight(mc.map->time_of(ph)) : 1.0f;
    if (!(in_time > 0)) return;
    Rgb power = Rgb::load(ph.power);
    if (mc.spectral && !photon_at_wavelength(mc, mc.map->lambda_of(ph), lambda, lambda_window, power)) return;
    if (!ng_encoded) ng_code = encode_octahedral(ng), ng_encoded = true;
    if (ph.normal != ng_code && !(dot(decode_octahedral(ph.normal), ng) > 0)) return;
    const Vec3f wp = decode_octahedral(ph.dir);
    float wp_arr[3], f[3], pdf_fwd = 0, pdf_rev = 0;
    wp.store(wp_arr);
    if (lambda > 0)
      mc.spectral->bsdf_eval(mc.host, &ix, wo_arr, wp_arr, NIMBUS_MODE_RADIANCE, lambda, f, &pdf_fwd,
                             &pdf_rev);
    else
      mc.bsdf->eval(mc.host, &ix, wo_arr, wp_arr, NIMBUS_MODE_RADIANCE, f, &pdf_fwd, &pdf_rev);
    ++evaluated;
    density_count += ph.light() < mc.density_weight.size() ? mc.density_weight[ph.light()] : 1.0f;
    const Rgb fr = Rgb::load(f);
    if (is_black(fr)) return;
    // The light-tracing technique, with the photon's density against its (light_paths.hpp).
    Mis lt = 0;
    if (s == 1 ? mis_state.lt_first > 0 : mis_state.lt > 0) {
      const Mis rho = std::exp2(Mis(mc.map->lt_of(ph)));
      if (rho > 0) lt = mis_state.lt_times(s == 1 ? rho : mis(Mis(pdf_rev)) * rho, s == 1);
    }
    const float w = merge_weight(ph.A, ph.B, ph.b_valid(), ph.prev_rough(), pdf_fwd, pdf_rev, eta, m_neff,
                                 m_neff_b, mis_state.gamma_sum(k), mis_state.clamped, eta_splat, lt);
    const float kernel = kernel_norm * (1 - d2 / r2) * in_time;
    const Rgb c = fr * power * (w * kernel);
    if (!is_finite(c) || is_black(c)) return;
    // The same merge without light paths, for their trial (light_path_trial.hpp).
    const Rgb c_without =
        lt > 0 ? c * (merge_weight(ph.A, ph.B, ph.b_valid(), ph.prev_rough(), pdf_fwd, pdf_rev, eta, m_neff,
                                   m_neff_b, mis_state.gamma_sum(k), mis_state.clamped, eta_splat) /
                      w)
               : c;
    const uint32_t path = mc.map->path_of(ph);
    if (mc.path_use) mc.path_use->mark(path);
    if (mc.ids.lightmix)
      rec.add_merge(beta * c * inv_paths, (*mc.light_group)[ph.light()], mc.ids,
                    beta * c_without * inv_paths);
    sum += c, sum_without += c_without;
    split += path & 1u ? -c : c;
  });
  if (is_black(sum)) return {leaves, evaluated, 0.0f, density_count};
  rec.merge_split += luminance(beta * split * inv_paths);
  const Rgb light = beta * sum * inv_paths;
  if (!mc.ids.lightmix) rec.add_merge(light, 0, mc.ids, beta * sum_without * inv_paths);
  return {leaves, evaluated, luminance(light), density_count};
}

}  // namespace nimbus::caustics
