// Dispatch over light kinds, and the parts every infinite light shares (the emission disk).
#include "lights/light.hpp"

#include <cstring>

#include <nimbus/cpp/sampling.hpp>

namespace nimbus {

Vec3f environment_sample(const EnvironmentLight &env, float u0, float u1, float &pdf, Rgb &radiance);

namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

// An incident sample from infinitely far away along wi (towards the light).
void set_infinite_incident(const LightScene &scene, const Vec3f &p, const Vec3f &wi, const Rgb &L, float pdf,
                           uint32_t flags, nimbus_light_incident_t &out) {
  wi.store(out.wi);
  out.dist = kInfinity;
  // A point beyond the scene's bounding sphere, for spawn_ray_to.
  (p + wi * (2 * scene.radius + length(p - scene.center))).store(out.p);
  L.store(out.L);
  out.pdf = pdf;
  out.flags = flags | NIMBUS_LIGHT_INFINITE;
}

// The area density of an infinite light's photon origins: uniform on the disk of the scene's bounding
// sphere.
float infinite_pdf_pos(const LightScene &scene) { return 1 / (kPi * sqr(scene.radius)); }

// A photon arriving from direction `to_light` (unit, towards the light): starts on the disk of the
// scene's bounding sphere that faces the light, and travels along -to_light.
void set_infinite_emission(const LightScene &scene, const Vec3f &to_light, float u0, float u1, const Rgb &L,
                           float pdf_dir, uint32_t flags, nimbus_light_emission_t &out) {
  const Frame f = Frame::from_normal(to_light);
  const Vec2f d = sample_uniform_disk_concentric(u0, u1);
  const Vec3f org = scene.center + (to_light + f.s * d.x + f.t * d.y) * scene.radius;
  org.store(out.org);
  (-to_light).store(out.dir);
  (-to_light).store(out.n);
  L.store(out.Le);
  out.pdf_pos = infinite_pdf_pos(scene);
  out.pdf_dir = pdf_dir;
  out.flags = flags | NIMBUS_LIGHT_INFINITE;
}

}  // namespace

void light_sample_incident(const Light &light, const LightScene &scene, const nimbus_interaction_t &ref,
                           const float u[2], nimbus_light_incident_t &out) {
  std::memset(&out, 0, sizeof(out));
  const Vec3f p = Vec3f::load(ref.p);
  std::visit(
      Overloaded{
          [&](const PointLight &l) {
            const Vec3f d = l.position - p;
            const float dist2 = length_squared(d);
            if (!(dist2 > 0)) return;
            const float dist = std::sqrt(dist2);
            (d / dist).store(out.wi);
            out.dist = dist;
            l.position.store(out.p);
            (l.intensity / dist2).store(out.L);
            out.pdf = 1;
            out.flags = NIMBUS_LIGHT_DELTA_POSITION;
          },
          [&](const SpotLight &l) {
            const Vec3f d = l.position - p;
            const float dist2 = length_squared(d);
            if (!(dist2 > 0)) return;
            const float dist = std::sqrt(dist2);
            const Vec3f wi = d / dist;
            wi.store(out.wi);
            out.dist = dist;
            l.position.store(out.p);
            (l.intensity * (l.falloff(dot(-wi, l.frame.n)) / dist2)).store(out.L);
            out.pdf = 1;
            out.flags = NIMBUS_LIGHT_DELTA_POSITION;
          },
          [&](const AreaLight &l) { area_sample_incident(l, *scene.geometry, p, u, out); },
          [&](const SunLight &l) {
            if (l.is_delta()) {
              set_infinite_incident(scene, p, l.to_sun, l.radiance, 1, NIMBUS_LIGHT_DELTA_DIRECTION, out);
              return;
            }
            const Vec3f wi = l.frame.to_world(sample_uniform_cone(u[0], u[1], l.cos_half_angle));
            set_infinite_incident(scene, p, wi, l.radiance, uniform_cone_pdf(l.cos_half_angle), 0, out);
          },
          [&](const EnvironmentLight &l) {
            float pdf = 0;
            Rgb radiance;
            const Vec3f wi = environment_sample(l, u[0], u[1], pdf, radiance);
            if (!(pdf > 0)) return;
            set_infinite_incident(scene, p, wi, radiance, pdf, 0, out);
          },
      },
      light.kind);
}

float light_pdf_incident(const Light &light, const LightScene &scene, const nimbus_interaction_t &ref,
                         const Vec3f &wi, const nimbus_interaction_t *on_light) {
  return std::visit(
      Overloaded{
          [&](const AreaLight &l) {
            return on_light ? area_pdf_incident(l, *scene.geometry, Vec3f::load(ref.p), wi, *on_light) : 0.0f;
          },
          [&](const SunLight &l) {
            return !l.is_delta() && dot(wi, l.to_sun) >= l.cos_half_angle ? uniform_cone_pdf(l.cos_half_angle)
                                                                          : 0.0f;
          },
          [&](const EnvironmentLight &l) { return l.pdf(wi); },
          [](const auto &) { return 0.0f; },
      },
      light.kind);
}

Rgb light_eval_emitted(const Light &light, const nimbus_interaction_t &on_light, const Vec3f &wo) {
  const auto *a = std::get_if<AreaLight>(&light.kind);
  if (!a || !(a->two_sided || dot(Vec3f::load(on_light.ng), wo) > 0)) return Rgb(0);
  return a->radiance;
}

Rgb light_eval_infinite(const Light &light, const Vec3f &dir) {
  if (const auto *s = std::get_if<SunLight>(&light.kind))
    return !s->is_delta() && dot(dir, s->to_sun) >= s->cos_half_angle ? s->radiance : Rgb(0);
  if (const auto *e = std::get_if<EnvironmentLight>(&light.kind)) return e->lookup(dir);
  return Rgb(0);
}

void light_sample_emission(const Light &light, const LightScene &scene, const float u[4],
                           nimbus_light_emission_t &out) {
  std::memset(&out, 0, sizeof(out));
  std::visit(Overloaded{
                 [&](const PointLight &l) {
                   l.position.store(out.org);
                   sample_uniform_sphere(u[2], u[3]).store(out.dir);
                   l.intensity.store(out.Le);
                   out.pdf_pos = 1;
                   out.pdf_dir = kUniformSpherePdf;
                   out.flags = NIMBUS_LIGHT_DELTA_POSITION;
                 },
                 [&](const SpotLight &l) {
                   const Vec3f local = sample_uniform_cone(u[2], u[3], l.cos_falloff_end);
                   l.position.store(out.org);
                   l.frame.to_world(local).store(out.dir);
                   (l.intensity * l.falloff(local.z)).store(out.Le);
                   out.pdf_pos = 1;
                   out.pdf_dir = uniform_cone_pdf(l.cos_falloff_end);
                   out.flags = NIMBUS_LIGHT_DELTA_POSITION;
                 },
                 [&](const AreaLight &l) { area_sample_emission(l, *scene.geometry, u, out); },
                 [&](const SunLight &l) {
                   if (l.is_delta()) {
                     set_infinite_emission(scene, l.to_sun, u[0], u[1], l.radiance, 1,
                                           NIMBUS_LIGHT_DELTA_DIRECTION, out);
                     return;
                   }
                   const Vec3f w = l.frame.to_world(sample_uniform_cone(u[2], u[3], l.cos_half_angle));
                   set_infinite_emission(scene, w, u[0], u[1], l.radiance, uniform_cone_pdf(l.cos_half_angle),
                                         0, out);
                 },
                 [&](const EnvironmentLight &l) {
                   float pdf = 0;
                   Rgb radiance;
                   const Vec3f w = environment_sample(l, u[2], u[3], pdf, radiance);
                   if (!(pdf > 0)) return;
                   set_infinite_emission(scene, w, u[0], u[1], radiance, pdf, 0, out);
                 },
             },
             light.kind);
}

// Each case mirrors light_sample_emission: the same tests and the same expressions, so that a sampled
// photon's Le, pdf_pos and pdf_dir come back as they were sampled (up to the rounding of the direction).
Rgb light_eval_emission(const Light &light, const Vec3f *n, const Vec3f &dir) {
  return std::visit(
      Overloaded{
          [&](const PointLight &l) { return l.intensity; },
          [&](const SpotLight &l) { return l.intensity * l.falloff(dot(dir, l.frame.n)); },
          [&](const AreaLight &l) { return n && (l.two_sided || dot(*n, dir) > 0) ? l.radiance : Rgb(0); },
          [&](const SunLight &l) {
            return l.is_delta() || dot(-dir, l.to_sun) >= l.cos_half_angle ? l.radiance : Rgb(0);
          },
          [&](const EnvironmentLight &l) { return l.lookup(-dir); },
      },
      light.kind);
}

void light_pdf_emission(const Light &light, const LightScene &scene, const Vec3f *n, const Vec3f &dir,
                        float &pdf_pos, float &pdf_dir) {
  pdf_pos = pdf_dir = 0;
  std::visit(Overloaded{
                 [&](const PointLight &) { pdf_pos = 1, pdf_dir = kUniformSpherePdf; },
                 [&](const SpotLight &l) {
                   pdf_pos = 1;
                   if (dot(dir, l.frame.n) >= l.cos_falloff_end)
                     pdf_dir = uniform_cone_pdf(l.cos_falloff_end);
                 },
                 [&](const AreaLight &l) { area_pdf_emission(l, *scene.geometry, n, dir, pdf_pos, pdf_dir); },
                 [&](const SunLight &l) {
                   pdf_pos = infinite_pdf_pos(scene);
                   if (l.is_delta())
                     pdf_dir = 1;
                   else if (dot(-dir, l.to_sun) >= l.cos_half_angle)
                     pdf_dir = uniform_cone_pdf(l.cos_half_angle);
                 },
                 [&](const EnvironmentLight &l) {
                   pdf_pos = infinite_pdf_pos(scene);
                   pdf_dir = l.pdf(-dir);
                 },
             },
             light.kind);
}

void light_fill_info(const Light &light, const LightScene &scene, nimbus_light_info_t &info) {
  info.group = light.group;
  info.power = light.power;
  const auto point_bounds = [&](const Vec3f &p) {
    p.store(info.bounds_min);
    p.store(info.bounds_max);
  };
  const auto scene_bounds = [&] {
    (scene.center - Vec3f(scene.radius)).store(info.bounds_min);
    (scene.center + Vec3f(scene.radius)).store(info.bounds_max);
  };
  std::visit(Overloaded{
                 [&](const PointLight &l) {
                   info.flags = NIMBUS_LIGHT_DELTA_POSITION;
                   point_bounds(l.position);
                   info.cos_theta_o = -1;
                   info.cos_theta_e = 0;
                 },
                 [&](const SpotLight &l) {
                   info.flags = NIMBUS_LIGHT_DELTA_POSITION;
                   point_bounds(l.position);
                   l.frame.n.store(info.axis);
                   info.cos_theta_o = 1;
                   info.cos_theta_e = l.cos_falloff_end;
                 },
                 [&](const AreaLight &l) { area_fill_info(l, *scene.geometry, info); },
                 [&](const SunLight &l) {
                   info.flags = NIMBUS_LIGHT_INFINITE | (l.is_delta() ? NIMBUS_LIGHT_DELTA_DIRECTION : 0u);
                   scene_bounds();
                   (-l.to_sun).store(info.axis);
                   info.cos_theta_o = 1;
                   info.cos_theta_e = l.cos_half_angle;
                 },
                 [&](const EnvironmentLight &) {
                   info.flags = NIMBUS_LIGHT_INFINITE;
                   scene_bounds();
                   info.cos_theta_o = -1;
                   info.cos_theta_e = 0;
                 },
             },
             light.kind);
  widen_info_over_motion(light, info);
}

}  // namespace nimbus
