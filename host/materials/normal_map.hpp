// Tangent-space normal mapping. Convention (OpenGL, as Blender and Substance export by default): a texel
// rgb encodes n = 2 rgb - 1 in the frame (tangent along dpdu, bitangent along dpdv, shading normal), so
// green points towards +v, up in the image; (0.5, 0.5, 1) is the unperturbed normal.
#pragma once

#include <cmath>

#include <nimbus/cpp/math.hpp>

namespace nimbus {

// The least cosine between a mapped normal and the geometric normal. A shading normal at or past the
// geometric horizon would put the BSDF's upper hemisphere inside the surface.
inline constexpr float kMinMappedCosine = 0.01f;

// A texel as a unit tangent-space normal. Values pointing into the surface (z <= 0, e.g. a colour image
// given by mistake) are lifted to just above the tangent plane rather than producing a NaN or a flip.
inline Vec3f decode_normal(const Rgb &texel) {
  Vec3f n = texel * 2.0f - Vec3f(1.0f);
  if (!is_finite(n)) return {0, 0, 1};
  n.z = std::max(n.z, kMinMappedCosine);
  return normalize(n);
}

// The shading normal ns tilted by the tangent-space normal m (unit, z > 0), kept on ng's side with a
// cosine of at least kMinMappedCosine. ns and ng are unit and on the same side; dpdu and dpdv may be
// degenerate (then the tangent is any direction perpendicular to ns). Never NaN: returns ns if all fails.
inline Vec3f apply_normal_map(const Vec3f &m, const Vec3f &ns, const Vec3f &ng, const Vec3f &dpdu,
                              const Vec3f &dpdv) {
  Frame f = Frame::from_normal_tangent(ns, dpdu);
  // A mirrored uv layout has dpdv against n x dpdu: flipping the bitangent keeps green meaning +v.
  if (dot(f.t, dpdv) < 0) f.t = -f.t;
  Vec3f n = f.s * m.x + f.t * m.y + ns * m.z;
  const float len = length(n);
  if (!(len > 0) || !std::isfinite(len)) return ns;
  n /= len;
  const float c = dot(n, ng);
  if (!(c >= kMinMappedCosine)) {
    // Rotate towards ng, keeping the azimuth: n = cos * ng + sin * (unit tangential part).
    const Vec3f tangential = n - ng * c;
    const float tl = length(tangential);
    n = tl > 0 ? tangential * (std::sqrt(1 - sqr(kMinMappedCosine)) / tl) + ng * kMinMappedCosine : ng;
  }
  return is_finite(n) ? n : ns;
}

}  // namespace nimbus
