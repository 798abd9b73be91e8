// An independent reference for caustics of delta lights: a small light tracer in double precision that
// shares no code with the host or the plugins (its own vectors, random numbers, intersections, Fresnel
// and camera projection), so that a bug there cannot hide in both the solver and its reference.
//
// The scene it knows is the one the delta-light tests render: a diffuse floor z = 0 (a square), one
// smooth glass sphere, planar mirrors (ideal, a constant reflectance), black axis-aligned boxes that
// absorb, one point, spot or delta sun light, and a pinhole camera looking straight down (up = +y).
// Pixels then map to floor squares of one size: a pixel's value is the mean radiance over its square,
// (albedo / pi) * (flux that landed in it) / (its area), as Nimbus's box filter averages over the pixel.
//
// Photons are aimed: directions (point, spot) or positions (sun) come from a mixture of cones or disks
// around "aims" (the ball, the camera's footprint, mirrors) and a small share of uniform emission over
// everything, and each photon carries emitted / (mixture density), so the estimate stays unbiased for
// light that reaches the image by any route (floor -> ball -> floor, mirror -> ball, ...).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <thread>
#include <vector>

namespace nimbus::testing::reference {

struct V3 {
  double x = 0, y = 0, z = 0;
};
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator*(V3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double norm(V3 a) { return std::sqrt(dot(a, a)); }
inline V3 unit(V3 a) { return a * (1 / norm(a)); }

constexpr double kPi = std::numbers::pi;

// An orthonormal basis around n (Duff et al. 2017).
inline void basis(V3 n, V3 &s, V3 &t) {
  const double sign = std::copysign(1.0, n.z), a = -1 / (sign + n.z), b = n.x * n.y * a;
  s = {1 + sign * n.x * n.x * a, sign * b, -sign * n.x};
  t = {b, sign + n.y * n.y * a, -n.y};
}

// xoshiro256**, seeded by splitmix64: a stream per batch, so batches are independent and the result
// does not depend on the thread count.
class Rng {
 public:
  explicit Rng(uint64_t seed) {
    for (uint64_t &w : s_) {
      seed += 0x9e3779b97f4a7c15ull;
      uint64_t z = seed;
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
      w = z ^ (z >> 31);
    }
  }
  double uniform() { return double(next() >> 11) * 0x1p-53; }

 private:
  static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  uint64_t next() {
    const uint64_t r = rotl(s_[1] * 5, 7) * 9, t = s_[1] << 17;
    s_[2] ^= s_[0], s_[3] ^= s_[1], s_[1] ^= s_[2], s_[0] ^= s_[3], s_[2] ^= t, s_[3] = rotl(s_[3], 45);
    return r;
  }
  uint64_t s_[4];
};

enum class LightKind { Point, Spot, Sun };

struct Mirror {
  V3 center, half_u, half_v;  // the rectangle center + a half_u + b half_v, |a|, |b| <= 1
  double reflectance = 1;
};
struct Box {
  V3 lo, hi;
};
struct Aim {
  V3 center;
  double radius = 0, weight = 0;  // the mixture weight of its cone (disk for the sun)
};

struct Scene {
  double floor_half = 20, albedo = 0.5;  // floor: |x|, |y| <= floor_half at z = 0
  V3 ball;
  double radius = 0.05, ior = 1.5;
  std::vector<Mirror> mirrors;
  std::vector<Box> blockers;
  LightKind light = LightKind::Point;
  V3 position;           // point, spot
  V3 direction;          // spot: the axis; sun: the direction light travels
  double intensity = 1;  // W/sr (spot: on the axis); sun: irradiance facing it (W/m^2)
  double cone_deg = 30, softness_deg = 5;
  V3 eye;  // camera above the floor, looking straight down, up = +y
  double fov_deg = 45;
  int width = 64, height = 48, max_depth = 10;
  std::vector<Aim> aims;         // where photons are aimed (the ball, the footprint, ...); see footprint()
  double uniform_weight = 0.02;  // share of photons emitted without aiming (covers every other route)

  double tan_half() const { return std::tan(fov_deg * kPi / 360); }
  double pixel_size() const { return 2 * eye.z * tan_half() / width; }  // side of a pixel's floor square
  // Floor point -> raster position, as host/world/camera.hpp's connect() for a pinhole looking down.
  bool raster(V3 p, double &rx, double &ry) const {
    const double s = eye.z * tan_half(), aspect = double(height) / width;
    rx = ((p.x - eye.x) / s + 1) * 0.5 * width;
    ry = (1 - (p.y - eye.y) / (s * aspect)) * 0.5 * height;
    return rx >= 0 && rx < width && ry >= 0 && ry < height;
  }
  // Raster position -> floor point (the inverse).
  V3 floor_point(double rx, double ry) const {
    const double s = eye.z * tan_half(), aspect = double(height) / width;
    return {eye.x + (2 * rx / width - 1) * s, eye.y + (1 - 2 * ry / height) * s * aspect, 0};
  }
  // The sphere around the floor the camera sees (an aim for direct light on the image).
  Aim footprint(double weight) const {
    const double fx = eye.z * tan_half(), fy = fx * height / width;
    return {{eye.x, eye.y, 0}, 1.01 * std::hypot(fx, fy), weight};
  }
  // Spot fall-off (docs/scene-format.md): full inside cone - softness, a smoothstep in cos to 0 at cone.
  double spot_falloff(double cos_theta) const {
    const double c_end = std::cos(cone_deg * kPi / 180),
                 c_start = std::cos((cone_deg - softness_deg) * kPi / 180);
    if (cos_theta >= c_start) return 1;
    if (cos_theta <= c_end) return 0;
    const double t = (cos_theta - c_end) / (c_start - c_end);
    return t * t * (3 - 2 * t);
  }
};

enum class Hit { None, Floor, Glass, Mirror, Black };

// Nearest hit along o + t d, t in (1e-9, tmax): its kind, distance t, normal n (the sphere's outward
// one) and, for a mirror, its reflectance.
inline Hit intersect(const Scene &sc, V3 o, V3 d, double &t, V3 &n, double tmax = 1e30,
                     double *refl = nullptr) {
  Hit hit = Hit::None;
  t = tmax;
  if (d.z != 0) {  // the floor
    const double tf = -o.z / d.z;
    const V3 p = o + d * tf;
    if (tf > 1e-9 && tf < t && std::abs(p.x) <= sc.floor_half && std::abs(p.y) <= sc.floor_half)
      t = tf, n = {0, 0, 1}, hit = Hit::Floor;
  }
  {  // the glass sphere: both roots, so that rays inside find their way out
    const V3 oc = o - sc.ball;
    const double b = dot(oc, d), c = dot(oc, oc) - sc.radius * sc.radius, disc = b * b - c;
    if (disc >= 0) {
      const double q = std::sqrt(disc);
      for (const double ts : {-b - q, -b + q})
        if (ts > 1e-9 && ts < t) {
          t = ts, n = (o + d * ts - sc.ball) * (1 / sc.radius), hit = Hit::Glass;
          break;
        }
    }
  }
  for (const Mirror &m : sc.mirrors) {
    const V3 nm = unit(cross(m.half_u, m.half_v));
    const double dn = dot(d, nm);
    if (dn == 0) continue;
    const double tm = dot(m.center - o, nm) / dn;
    if (!(tm > 1e-9 && tm < t)) continue;
    const V3 q = o + d * tm - m.center;
    if (std::abs(dot(q, m.half_u)) > dot(m.half_u, m.half_u) ||
        std::abs(dot(q, m.half_v)) > dot(m.half_v, m.half_v))
      continue;
    t = tm, n = nm, hit = Hit::Mirror;
    if (refl) *refl = m.reflectance;
  }
  for (const Box &bx : sc.blockers) {  // slabs
    double t0 = 1e-9, t1 = t;
    const double lo[3] = {bx.lo.x, bx.lo.y, bx.lo.z}, hi[3] = {bx.hi.x, bx.hi.y, bx.hi.z};
    const double oo[3] = {o.x, o.y, o.z}, dd[3] = {d.x, d.y, d.z};
    for (int a = 0; a < 3 && t0 <= t1; ++a) {
      double ta = (lo[a] - oo[a]) / dd[a], tb = (hi[a] - oo[a]) / dd[a];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta), t1 = std::min(t1, tb);
    }
    if (t0 <= t1 && t0 < t) t = t0, hit = Hit::Black;
  }
  return hit;
}

// Exact unpolarised Fresnel reflectance; cos_i > 0, eta = n_incident / n_transmitted; 1 under TIR.
inline double fresnel(double cos_i, double eta, double &cos_t) {
  const double sin2_t = eta * eta * (1 - cos_i * cos_i);
  if (sin2_t >= 1) return 1;
  cos_t = std::sqrt(1 - sin2_t);
  const double rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t),
               rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return (rs * rs + rp * rp) / 2;
}

// The camera sees floor point p (nothing between it and the pinhole).
inline bool camera_sees(const Scene &sc, V3 p) {
  double t;
  V3 n;
  const V3 d = sc.eye - p;
  const double len = norm(d);
  return intersect(sc, p, d * (1 / len), t, n, len) == Hit::None;
}

// Every ray of the pixel (a k x k grid including its edges) sees the floor and nothing else: such pixels
// hold floor radiance only, which is all the reference computes.
inline bool pixel_sees_floor_only(const Scene &sc, int x, int y, int k = 6) {
  for (int i = 0; i <= k; ++i)
    for (int j = 0; j <= k; ++j)
      if (!camera_sees(sc, sc.floor_point(x + double(i) / k, y + double(j) / k))) return false;
  return true;
}

struct Image {
  int width = 0, height = 0, batches = 0;
  std::vector<double> total, glass;  // per batch, then pixel: radiance (glass: paths through the ball)
  double value(int b, int x, int y) const { return total[(size_t(b) * height + y) * width + x]; }
};

// One lobe of the emission mixture: for point and spot lights a uniform cone of directions towards an
// aim (size = 1 - cos of its half angle, kept exact for far, small aims); for the sun a uniform disk in
// the plane through the origin perpendicular to the sun (centre = the aim projected, size = radius).
struct Lobe {
  V3 center, s, t;
  double size = 0, weight = 0;
  bool contains(const Scene &sc, V3 v) const {  // v: a direction, or a point of the sun's plane
    if (sc.light == LightKind::Sun) return dot(v - center, v - center) < size * size;
    return dot(v, center) > 0 && dot(cross(v, center), cross(v, center)) < size * (2 - size);
  }
  double density(const Scene &sc) const {  // per steradian, or per square metre of the sun's plane
    return sc.light == LightKind::Sun ? 1 / (kPi * size * size) : 1 / (2 * kPi * size);
  }
};

// One photon path from the light; adds its radiance contributions to batch images `img` and `gl`.
inline void trace_photon(const Scene &sc, const std::vector<Lobe> &lobes, Rng &rng, double *img, double *gl) {
  const double u0 = rng.uniform(), u1 = rng.uniform(), phi = 2 * kPi * rng.uniform();
  // The mixture: a lobe by its weight, or the uniform share.
  size_t pick = lobes.size();
  double acc = 0;
  for (size_t k = 0; k < lobes.size() && pick == lobes.size(); ++k)
    if (u0 < (acc += lobes[k].weight)) pick = k;
  V3 o, d;
  double flux = 0;
  if (sc.light != LightKind::Sun) {
    if (pick < lobes.size()) {
      const Lobe &l = lobes[pick];
      const double omc = u1 * l.size, sin_t = std::sqrt(omc * (2 - omc));
      d = unit(l.s * (sin_t * std::cos(phi)) + l.t * (sin_t * std::sin(phi)) + l.center * (1 - omc));
    } else {
      const double z = 1 - 2 * u1, r = std::sqrt(std::max(0.0, 1 - z * z));
      d = {r * std::cos(phi), r * std::sin(phi), z};
    }
    double pdf = sc.uniform_weight / (4 * kPi);
    for (const Lobe &l : lobes)
      if (l.contains(sc, d)) pdf += l.weight * l.density(sc);
    const double emitted = sc.light == LightKind::Spot
                               ? sc.intensity * sc.spot_falloff(dot(d, unit(sc.direction)))
                               : sc.intensity;
    o = sc.position, flux = emitted / pdf;
  } else {
    // The uniform share is a disk that covers the whole floor and everything on it.
    d = unit(sc.direction);
    V3 s, t;
    basis(d, s, t);
    const double big = 1.5 * sc.floor_half * std::sqrt(2.0);
    const double r = std::sqrt(u1) * (pick < lobes.size() ? lobes[pick].size : big);
    const V3 q =
        (pick < lobes.size() ? lobes[pick].center : V3{}) + s * (r * std::cos(phi)) + t * (r * std::sin(phi));
    double pdf = sc.uniform_weight / (kPi * big * big);
    for (const Lobe &l : lobes)
      if (l.contains(sc, q)) pdf += l.weight * l.density(sc);
    o = q - d * (8 * sc.floor_half), flux = sc.intensity / pdf;
  }
  bool through_glass = false;
  const double to_radiance = sc.albedo / kPi / (sc.pixel_size() * sc.pixel_size());
  for (int segments = 1; segments < sc.max_depth; ++segments) {  // a deposit needs segments + 1 <= max
    double t;
    V3 n;
    double reflectance = 1;
    const Hit h = intersect(sc, o, d, t, n, 1e30, &reflectance);
    if (h == Hit::None || h == Hit::Black) return;
    const V3 p = o + d * t;
    if (h == Hit::Glass) {
      through_glass = true;
      double cos_i = -dot(d, n), eta = 1 / sc.ior, cos_t = 0;
      if (cos_i < 0) cos_i = -cos_i, n = n * -1, eta = sc.ior;  // leaving the ball: n against d
      if (rng.uniform() < fresnel(cos_i, eta, cos_t)) {
        d = d + n * (2 * cos_i), o = p + n * 1e-9;
      } else {
        d = unit(d * eta + n * (eta * cos_i - cos_t)), o = p - n * 1e-9;
      }
      continue;
    }
    if (h == Hit::Mirror) {
      flux *= reflectance;
      const double dn = dot(d, n);
      d = d - n * (2 * dn), o = p - n * (std::copysign(1e-9, dn));
      continue;
    }
    // The floor: deposit where the camera sees it, then a cosine bounce with Russian roulette.
    double rx, ry;
    if (sc.raster(p, rx, ry) && camera_sees(sc, p)) {
      const size_t i = size_t(int(ry)) * sc.width + size_t(int(rx));
      img[i] += flux * to_radiance;
      if (through_glass) gl[i] += flux * to_radiance;
    }
    if (rng.uniform() >= sc.albedo) return;
    const double r = std::sqrt(rng.uniform()), phi = 2 * kPi * rng.uniform();
    d = {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1 - r * r))}, o = {p.x, p.y, 1e-9};
  }
}

// The reference image: `photons` paths in `batches` independent batches (each an unbiased image, so
// their spread gives the standard error), on up to `threads` threads.
inline Image trace(const Scene &sc, uint64_t photons, int batches = 16, uint64_t seed = 1, int threads = 2) {
  double sum = sc.uniform_weight;
  for (const Aim &a : sc.aims) sum += a.weight;
  std::vector<Lobe> lobes;
  for (const Aim &a : sc.aims) {
    Lobe l;
    l.weight = a.weight / sum;
    if (sc.light == LightKind::Sun) {
      const V3 d = unit(sc.direction);
      l.center = a.center - d * dot(a.center, d), l.size = a.radius;
    } else {
      const V3 to = a.center - sc.position;
      const double s2 = a.radius * a.radius / dot(to, to);
      l.center = unit(to), l.size = s2 / (1 + std::sqrt(1 - s2));
      basis(l.center, l.s, l.t);
    }
    lobes.push_back(l);
  }
  Scene scaled = sc;
  scaled.uniform_weight /= sum;
  Image out;
  out.width = sc.width, out.height = sc.height, out.batches = batches;
  const size_t pixels = size_t(sc.width) * sc.height;
  out.total.assign(pixels * batches, 0), out.glass.assign(pixels * batches, 0);
  const uint64_t per_batch = photons / batches;
  std::vector<std::thread> pool;
  for (int w = 0; w < threads; ++w)
    pool.emplace_back([&, w] {
      for (int b = w; b < batches; b += threads) {
        Rng rng(seed * 0x100000001b3ull + uint64_t(b));
        double *img = &out.total[pixels * b], *gl = &out.glass[pixels * b];
        for (uint64_t p = 0; p < per_batch; ++p) trace_photon(scaled, lobes, rng, img, gl);
        for (size_t i = 0; i < pixels; ++i) img[i] /= double(per_batch), gl[i] /= double(per_batch);
      }
    });
  for (std::thread &t : pool) t.join();
  return out;
}

}  // namespace nimbus::testing::reference
