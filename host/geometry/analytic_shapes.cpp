#include "geometry/analytic_shapes.hpp"

#include <algorithm>
#include <cmath>

namespace nimbus {
namespace {

void bounds_fn(const RTCBoundsFunctionArguments *args) {
  const auto *s = static_cast<const ShapeRecord *>(args->geometryUserPtr);
  Vec3f lo, hi;
  if (s->type == ShapeType::Sphere) {
    lo = s->center - Vec3f(s->radius), hi = s->center + Vec3f(s->radius);
  } else {
    // Disk: the extent along each axis is r * sqrt(1 - n_axis^2).
    const Vec3f e{s->radius * safe_sqrt(1 - sqr(s->normal.x)), s->radius * safe_sqrt(1 - sqr(s->normal.y)),
                  s->radius * safe_sqrt(1 - sqr(s->normal.z))};
    lo = s->center - e, hi = s->center + e;
  }
  // Pad by 2^-16 of the coordinates (hundreds of ulps) so that rounding never culls a hit on the boundary.
  const float pad = std::max(max_component(abs(s->center)) + s->radius, 0x1p-100f) * 0x1p-16f;
  args->bounds_o->lower_x = lo.x - pad, args->bounds_o->lower_y = lo.y - pad,
  args->bounds_o->lower_z = lo.z - pad;
  args->bounds_o->upper_x = hi.x + pad, args->bounds_o->upper_y = hi.y + pad,
  args->bounds_o->upper_z = hi.z + pad;
}

// Nearest t in (tnear, tfar] where the ray meets the shape, or a negative value.
double hit_distance(const ShapeRecord &s, const double org[3], const double dir[3], double tnear,
                    double tfar) {
  if (s.type == ShapeType::Sphere) {
    // Solve |o + t d - c|^2 = r^2 with the numerically stable form (pbrt-v4 / Ray Tracing Gems ch. 7):
    // discriminant from the perpendicular distance avoids cancellation for large distances. That
    // distance squared times a is |oc x d|^2, which needs no division: a miss returns before any.
    const double oc[3] = {org[0] - s.center.x, org[1] - s.center.y, org[2] - s.center.z};
    const double a = dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2];
    const double b = oc[0] * dir[0] + oc[1] * dir[1] + oc[2] * dir[2];  // half of the usual b
    const double r = s.radius;
    const double cx = oc[1] * dir[2] - oc[2] * dir[1], cy = oc[2] * dir[0] - oc[0] * dir[2],
                 cz = oc[0] * dir[1] - oc[1] * dir[0];
    const double disc = a * (r * r) - (cx * cx + cy * cy + cz * cz);
    if (disc < 0) return -1;
    const double root = std::sqrt(disc);
    const double q = (b > 0) ? -(b + root) : -(b - root);
    double t0 = q / a, t1 = (oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - r * r) / q;
    if (q == 0) t0 = t1 = -b / a;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > tnear && t0 <= tfar) return t0;
    if (t1 > tnear && t1 <= tfar) return t1;
    return -1;
  }
  const double n[3] = {s.normal.x, s.normal.y, s.normal.z};
  const double denom = n[0] * dir[0] + n[1] * dir[1] + n[2] * dir[2];
  if (denom == 0) return -1;
  const double t =
      ((s.center.x - org[0]) * n[0] + (s.center.y - org[1]) * n[1] + (s.center.z - org[2]) * n[2]) / denom;
  if (!(t > tnear && t <= tfar)) return -1;
  double d2 = 0;
  for (int i = 0; i < 3; ++i) {
    const double p = org[i] + t * dir[i] - (&s.center.x)[i];
    d2 += p * p;
  }
  return d2 <= double(s.radius) * s.radius ? t : -1;
}

void intersect_fn(const RTCIntersectFunctionNArguments *args) {
  // Embree calls user geometry with N == 1 for rtcIntersect1 (the only entry point the host uses).
  if (!args->valid[0]) return;
  const auto *s = static_cast<const ShapeRecord *>(args->geometryUserPtr);
  RTCRayHit *rh = reinterpret_cast<RTCRayHit *>(args->rayhit);
  const double org[3] = {rh->ray.org_x, rh->ray.org_y, rh->ray.org_z};
  const double dir[3] = {rh->ray.dir_x, rh->ray.dir_y, rh->ray.dir_z};
  const double t = hit_distance(*s, org, dir, rh->ray.tnear, rh->ray.tfar);
  if (t < 0) return;
  rh->ray.tfar = float(t);
  rh->hit.u = 0, rh->hit.v = 0;
  rh->hit.Ng_x = 0, rh->hit.Ng_y = 0, rh->hit.Ng_z = 1;
  rh->hit.primID = args->primID;
  rh->hit.geomID = args->geomID;
  rh->hit.instID[0] = args->context->instID[0];
}

void occluded_fn(const RTCOccludedFunctionNArguments *args) {
  if (!args->valid[0]) return;
  const auto *s = static_cast<const ShapeRecord *>(args->geometryUserPtr);
  RTCRay *ray = reinterpret_cast<RTCRay *>(args->ray);
  const double org[3] = {ray->org_x, ray->org_y, ray->org_z};
  const double dir[3] = {ray->dir_x, ray->dir_y, ray->dir_z};
  if (hit_distance(*s, org, dir, ray->tnear, ray->tfar) >= 0) ray->tfar = -kInfinity;
}

}  // namespace

RTCGeometry make_analytic_geometry(RTCDevice device, const ShapeRecord &shape) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(g, 1);
  rtcSetGeometryUserData(g, const_cast<ShapeRecord *>(&shape));
  rtcSetGeometryBoundsFunction(g, bounds_fn, nullptr);
  rtcSetGeometryIntersectFunction(g, intersect_fn);
  rtcSetGeometryOccludedFunction(g, occluded_fn);
  rtcCommitGeometry(g);
  return g;
}

}  // namespace nimbus
