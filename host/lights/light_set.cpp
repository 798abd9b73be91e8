#include "lights/light_set.hpp"

#include <map>

#include "lights/sky_model.hpp"

namespace nimbus {
namespace {

// LightMix: a light without a `group:` is its own group ("light<index>") while the scene has at most
// this many lights; beyond that ungrouped lights share the group "default" (no one mixes 10,000 layers).
constexpr uint32_t kMaxImplicitGroups = 16;

float triangle_area(const MeshData &m, size_t t) {
  const Vec3f &a = m.positions[m.indices[3 * t]], &b = m.positions[m.indices[3 * t + 1]],
              &c = m.positions[m.indices[3 * t + 2]];
  return 0.5f * length(cross(b - a, c - a));
}

}  // namespace

Expected<LightSet> LightSet::build(const SceneDesc &desc, GeometryScene &geo) {
  LightSet set;
  set.scene_ = {&geo, geo.sphere_center(), std::max(geo.sphere_radius(), 1e-6f)};
  const float disk_area = kPi * sqr(set.scene_.radius);
  std::vector<std::string> groups;  // as written, per light
  const auto add = [&](Light l, const std::string &group) {
    if (l.infinite()) set.infinite_.push_back(set.count());
    set.lights_.push_back(std::move(l));
    groups.push_back(group);
  };
  const LightDesc *sun_desc = nullptr;
  for (const LightDesc &ld : desc.lights) {
    Light l;
    switch (ld.type) {
      case LightType::Point:
        l.kind = PointLight{ld.position, ld.intensity};
        l.motion = ld.motion;
        l.power = 4 * kPi * luminance(ld.intensity);
        break;
      case LightType::Spot: {
        SpotLight s;
        s.position = ld.position;
        s.frame = Frame::from_normal(normalize(ld.direction));
        s.intensity = ld.intensity;
        const float cone = radians(clamp(ld.cone_degrees, 0.01f, 180.0f));
        const float soft = radians(clamp(ld.softness_degrees, 0.0f, ld.cone_degrees));
        s.cos_falloff_end = std::cos(cone);
        s.cos_falloff_start = std::cos(cone - soft);
        l.power = luminance(ld.intensity) * 2 * kPi *
                  ((1 - s.cos_falloff_start) + (s.cos_falloff_start - s.cos_falloff_end) / 2);
        l.kind = s;
        l.motion = ld.motion;
        break;
      }
      case LightType::Sun: {
        SunLight s;
        s.to_sun = -normalize(ld.direction);
        s.frame = Frame::from_normal(s.to_sun);
        const float half = radians(ld.angular_diameter_degrees) / 2;
        if (half > 0) {
          s.cos_half_angle = std::cos(half);
          // Radiance of a uniform disk that gives the requested irradiance at normal incidence:
          // E = L * pi * sin^2(half) (the projected solid angle of the cone).
          s.radiance = ld.irradiance / (kPi * sqr(std::sin(half)));
        } else {
          s.radiance = ld.irradiance;
        }
        l.power = luminance(ld.irradiance) * disk_area;
        l.kind = s;
        sun_desc = &ld;
        break;
      }
    }
    add(std::move(l), ld.group);
  }
  for (uint32_t s = 0; s < desc.shapes.size(); ++s) {
    const ShapeDesc &sd = desc.shapes[s];
    if (is_black(sd.emission)) continue;
    AreaLight a;
    a.shape = s;
    a.radiance = sd.emission;
    a.two_sided = sd.two_sided;
    if (sd.type != ShapeType::Sphere && sd.type != ShapeType::Disk) {
      std::vector<double> areas(sd.mesh.indices.size() / 3);
      for (size_t t = 0; t < areas.size(); ++t) areas[t] = triangle_area(sd.mesh, t);
      a.triangles = AliasTable(areas);
      if (a.triangles.empty()) continue;  // degenerate mesh: emits nothing and cannot be sampled
    }
    Light l;
    l.power = kPi * geo.shapes()[s].area * luminance(sd.emission) * (sd.two_sided ? 2 : 1);
    l.kind = std::move(a);
    geo.shapes()[s].light_id = set.count();
    add(std::move(l), sd.group);
  }
  const EnvironmentDesc &ed = desc.environment;
  if (ed.type != EnvironmentType::None) {
    EnvironmentLight env;
    if (ed.type == EnvironmentType::Map) {
      auto loaded = load_environment_map(ed.map);
      if (!loaded) return loaded.error();
      env = std::move(loaded.value());
    } else if (ed.type == EnvironmentType::Sky) {
      const Vec3f to_sun = sun_desc ? -normalize(sun_desc->direction) : normalize(ed.sun_direction);
      // 256 x 128 (1.4 degrees a texel) interpolated bilinearly: the sky is smooth (the sun is its own
      // light), and 512 KB of texels stay in a core's L2 where 512 x 256 missed on most escaped rays.
      env.width = 256, env.height = 128, env.bilinear = true;
      env.map = bake_sky(to_sun, ed.turbidity, env.width, env.height);
    } else {
      env.color = ed.color;
    }
    for (Rgb &c : env.map) c *= ed.scale;
    env.color *= ed.scale;
    env.rotate_radians = radians(ed.rotate_degrees);
    const double integral = env.finish_build();
    if (integral > 0) {
      Light l;
      l.power = float(integral) * disk_area;
      l.kind = std::move(env);
      add(std::move(l), ed.group.empty() ? "environment" : ed.group);
    }
  }
  std::map<std::string, uint32_t> by_name;
  for (uint32_t i = 0; i < set.count(); ++i) {
    const std::string name = !groups[i].empty()                  ? groups[i]
                             : set.count() <= kMaxImplicitGroups ? "light" + std::to_string(i)
                                                                 : "default";
    auto [it, inserted] = by_name.emplace(name, uint32_t(set.group_names_.size()));
    if (inserted) set.group_names_.push_back(name);
    set.lights_[i].group = it->second;
  }
  return set;
}

}  // namespace nimbus
