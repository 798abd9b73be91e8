// Emissive shapes: uniform sampling by area, or by solid angle for spheres seen from outside.
#include <nimbus/cpp/sampling.hpp>
#include "lights/light.hpp"

namespace nimbus {
namespace {

struct SurfacePoint {
  Vec3f p, n;
  Vec3f error;  // bound on each coordinate's rounding error in p
  float pdf_area = 0;
};

// Points are uniform by area on every shape (meshes: triangles picked by area).
float area_pdf(const ShapeRecord &s) { return s.area > 0 ? 1 / s.area : 0; }

SurfacePoint sample_area(const AreaLight &a, const ShapeRecord &s, float u0, float u1) {
  SurfacePoint sp;
  switch (s.type) {
    case ShapeType::Sphere: {
      const Vec3f d = sample_uniform_sphere(u0, u1);
      sp.p = s.center + d * s.radius, sp.n = d;
      sp.error = sphere_point_error(s.center, d, s.radius);
      break;
    }
    case ShapeType::Disk: {
      const Vec2f d = sample_uniform_disk_concentric(u0, u1);
      const Frame f = Frame::from_normal(s.normal);
      sp.p = s.center + (f.s * d.x + f.t * d.y) * s.radius, sp.n = s.normal;
      sp.error = disk_point_error(sp.p, s.center);
      break;
    }
    default: {
      float u0r = 0;
      const int64_t t = a.triangles.sample(u0, nullptr, &u0r);
      const MeshData &m = *s.mesh;
      const Vec2f b = sample_uniform_triangle(u0r, u1);
      const Vec3f &p0 = m.positions[m.indices[3 * t]], &p1 = m.positions[m.indices[3 * t + 1]],
                  &p2 = m.positions[m.indices[3 * t + 2]];
      sp.p = p0 * (1 - b.x - b.y) + p1 * b.x + p2 * b.y;
      sp.error = triangle_point_error(p0, p1, p2, 1 - b.x - b.y, b.x, b.y);
      sp.n = oriented_triangle_normal(m, uint32_t(t), b.x, b.y);
      break;
    }
  }
  sp.pdf_area = area_pdf(s);
  return sp;
}

// 1 - cos(theta_max) of the cone a sphere subtends from distance d, stable when the sphere is tiny.
float sphere_cone_one_minus_cos(float radius, float dist) {
  const float sin2 = sqr(radius / dist);
  return sin2 / (1 + safe_sqrt(1 - sin2));
}

bool outside_sphere(const ShapeRecord &s, const Vec3f &p, float &dist) {
  dist = length(s.center - p);
  return s.type == ShapeType::Sphere && dist > s.radius * 1.0001f;
}

bool emits_towards(const AreaLight &a, const Vec3f &n, const Vec3f &w) {
  return a.two_sided || dot(n, w) > 0;
}

}  // namespace

void area_sample_incident(const AreaLight &a, const GeometryScene &geo, const Vec3f &p, const float u[2],
                          nimbus_light_incident_t &out) {
  const ShapeRecord &s = geo.shapes()[a.shape];
  out.flags = NIMBUS_LIGHT_AREA;
  Vec3f lp, ln, error;
  float pdf, dc;
  if (outside_sphere(s, p, dc)) {
    // Sample the cone of directions the sphere subtends (pbrt-v4 Sphere::Sample(ctx)).
    const float omc = sphere_cone_one_minus_cos(s.radius, dc);
    const Frame f = Frame::from_normal((s.center - p) / dc);
    const float cos_theta = 1 - u[0] * omc;
    const float sin_theta = safe_sqrt(1 - cos_theta * cos_theta);
    const float phi = 2 * kPi * u[1];
    const Vec3f w = f.to_world({sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta});
    // Nearest intersection of p + t w with the sphere (tangent rays clamp to the tangent point).
    const float b = dot(w, s.center - p);
    const float t = b - safe_sqrt(sqr(s.radius) - (dc * dc - b * b));
    ln = normalize(p + w * t - s.center);
    lp = s.center + ln * s.radius;
    error = sphere_point_error(s.center, ln, s.radius);
    pdf = 1 / (2 * kPi * omc);
  } else {
    const SurfacePoint sp = sample_area(a, s, u[0], u[1]);
    lp = sp.p, ln = sp.n, error = sp.error;
    const Vec3f d = lp - p;
    const float dist2 = length_squared(d);
    if (!(dist2 > 0)) return;
    const float cos_l = std::abs(dot(ln, d)) / std::sqrt(dist2);
    if (!(cos_l > 0)) return;
    pdf = sp.pdf_area * dist2 / cos_l;
  }
  const Vec3f d = lp - p;
  const float dist = length(d);
  if (!(dist > 0) || !std::isfinite(pdf)) return;
  const Vec3f wi = d / dist;
  wi.store(out.wi);
  out.dist = dist;
  // The point shadow rays aim at: off the emitter by its rounding error, on the receiver's side, so the
  // emitter's own surface never occludes its sample however grazing the ray (pbrt-v4's SpawnRayTo
  // offsets both ends the same way).
  offset_origin(lp, ln, offset_distance(ln, error), -wi).store(out.p);
  ln.store(out.n);
  out.pdf = pdf;
  if (emits_towards(a, ln, -wi)) a.radiance.store(out.L);
}

float area_pdf_incident(const AreaLight &a, const GeometryScene &geo, const Vec3f &p, const Vec3f &wi,
                        const nimbus_interaction_t &on_light) {
  const ShapeRecord &s = geo.shapes()[a.shape];
  float dc;
  if (outside_sphere(s, p, dc)) return 1 / (2 * kPi * sphere_cone_one_minus_cos(s.radius, dc));
  const Vec3f lp = Vec3f::load(on_light.p), ln = Vec3f::load(on_light.ng);
  const float cos_l = std::abs(dot(ln, wi));
  if (!(cos_l > 0) || !(s.area > 0)) return 0;
  return length_squared(lp - p) / (cos_l * s.area);
}

void area_sample_emission(const AreaLight &a, const GeometryScene &geo, const float u[4],
                          nimbus_light_emission_t &out) {
  const SurfacePoint sp = sample_area(a, geo.shapes()[a.shape], u[0], u[1]);
  float u2 = u[2];
  Vec3f n = sp.n;
  float side_pmf = 1;
  if (a.two_sided) {  // pick a side, reusing u[2]
    side_pmf = 0.5f;
    if (u2 < 0.5f) {
      u2 *= 2;
    } else {
      u2 = (u2 - 0.5f) * 2, n = -n;
    }
  }
  const Vec3f local = sample_cosine_hemisphere(u2, u[3]);
  const Vec3f dir = Frame::from_normal(n).to_world(local);
  sp.p.store(out.org);
  dir.store(out.dir);
  n.store(out.n);
  a.radiance.store(out.Le);
  out.pdf_pos = sp.pdf_area;
  out.pdf_dir = cosine_hemisphere_pdf(local.z) * side_pmf;
  out.flags = NIMBUS_LIGHT_AREA | (a.two_sided ? NIMBUS_LIGHT_TWO_SIDED : 0u);
}

// The densities of area_sample_emission: uniform by area, cosine-weighted about the normal (two-sided:
// about the side dir leaves from, which it picks with probability 1/2).
void area_pdf_emission(const AreaLight &a, const GeometryScene &geo, const Vec3f *n, const Vec3f &dir,
                       float &pdf_pos, float &pdf_dir) {
  pdf_pos = area_pdf(geo.shapes()[a.shape]);
  if (!n) {
    pdf_dir = 0;
    return;
  }
  const float cos_theta = dot(*n, dir);
  pdf_dir =
      a.two_sided ? cosine_hemisphere_pdf(std::abs(cos_theta)) * 0.5f : cosine_hemisphere_pdf(cos_theta);
}

void area_fill_info(const AreaLight &a, const GeometryScene &geo, nimbus_light_info_t &info) {
  const ShapeRecord &s = geo.shapes()[a.shape];
  info.flags = NIMBUS_LIGHT_AREA | (a.two_sided ? NIMBUS_LIGHT_TWO_SIDED : 0u);
  info.area = s.area;
  Vec3f lo{kInfinity}, hi{-kInfinity};
  if (s.type == ShapeType::Sphere || s.type == ShapeType::Disk) {
    lo = s.center - Vec3f(s.radius), hi = s.center + Vec3f(s.radius);
  } else {
    for (const Vec3f &p : s.mesh->positions) lo = min(lo, p), hi = max(hi, p);
  }
  lo.store(info.bounds_min);
  hi.store(info.bounds_max);
  info.cos_theta_o = -1;  // normals in all directions (a bound; flat one-sided emitters could be tighter)
  info.cos_theta_e = 0;   // cosine emission: up to 90 degrees from each normal
  if (!a.two_sided && (s.type == ShapeType::Disk || s.type == ShapeType::Rectangle)) {
    const Vec3f n = s.type == ShapeType::Disk ? s.normal : oriented_triangle_normal(*s.mesh, 0, 0, 0);
    n.store(info.axis);
    info.cos_theta_o = 1;
  }
}

}  // namespace nimbus
