// Point and spot lights carried rigidly over the shutter: the light at a time is the resting light with
// its position (and a spot's axis) moved, so every routine of light.cpp serves a moving light unchanged.
#include <algorithm>
#include <cmath>
#include <vector>

#include "lights/light.hpp"

namespace nimbus {

const Light &light_at(const Light &light, float time, Light &moved) {
  if (!light.motion) return light;
  const Transform m = light.motion->at(time);
  moved.group = light.group;
  moved.power = light.power;
  if (const auto *p = std::get_if<PointLight>(&light.kind)) {
    moved.kind = PointLight{m.point(p->position), p->intensity};
  } else if (const auto *s = std::get_if<SpotLight>(&light.kind)) {
    SpotLight spot = *s;
    spot.position = m.point(s->position);
    spot.frame = Frame::from_normal(normalize(m.vector(s->frame.n)));
    moved.kind = spot;
  } else {
    return light;  // the parser lets only point and spot lights move
  }
  return moved;
}

void widen_info_over_motion(const Light &light, nimbus_light_info_t &info) {
  if (!light.motion || !light.motion->moves()) return;
  info.flags |= NIMBUS_LIGHT_MOVES;
  // Point and spot lights rest at a point: its positions (and the spot's axes) at dense times bound the
  // sweep once padded by the largest step between neighbours, which no point of a path between two
  // neighbouring samples can stray further than. A light tree must never see a bound that excludes the
  // light, or it would give the light zero importance where it shines.
  const Vec3f rest = Vec3f::load(info.bounds_min), rest_axis = Vec3f::load(info.axis);
  const bool has_axis = length_squared(rest_axis) > 0;
  const size_t samples = 8 * light.motion->steps().size() + 1;
  const float open = light.motion->open(), close = light.motion->close();
  Vec3f lo(kInfinity), hi(-kInfinity), mean_axis(0.0f), prev, prev_axis;
  float pad = 0, turn = 0;  // the largest distance and angle between neighbouring samples
  std::vector<Vec3f> axes;
  for (size_t i = 0; i < samples; ++i) {
    const Transform m = light.motion->at(open + (close - open) * float(i) / float(samples - 1));
    const Vec3f p = m.point(rest), a = has_axis ? normalize(m.vector(rest_axis)) : Vec3f(0.0f);
    if (i > 0) {
      pad = std::max(pad, length(p - prev));
      if (has_axis) turn = std::max(turn, std::acos(clamp(dot(a, prev_axis), -1.0f, 1.0f)));
    }
    lo = min(lo, p), hi = max(hi, p), mean_axis += a, prev = p, prev_axis = a;
    if (has_axis) axes.push_back(a);
  }
  (lo - Vec3f(pad)).store(info.bounds_min), (hi + Vec3f(pad)).store(info.bounds_max);
  if (!has_axis) return;
  const Vec3f axis = length_squared(mean_axis) > 0 ? normalize(mean_axis) : rest_axis;
  float spread = 0;
  for (const Vec3f &a : axes) spread = std::max(spread, std::acos(clamp(dot(axis, a), -1.0f, 1.0f)));
  axis.store(info.axis);
  // The cone of axes widens the cone of normals (cos_theta_o = 1 for a resting spot).
  info.cos_theta_o = std::min(info.cos_theta_o, std::cos(std::min(spread + turn, kPi)));
}

}  // namespace nimbus
