#include "lights/light_set.hpp"

#include <map>

namespace nimbus {
namespace {

// Lights without a group get their own, named after their kind and index ("light3").
uint32_t group_index(const std::string &group, uint32_t light_index, std::vector<std::string> &names,
                     std::map<std::string, uint32_t> &by_name) {
  const std::string name = group.empty() ? "light" + std::to_string(light_index) : group;
  auto [it, inserted] = by_name.emplace(name, uint32_t(names.size()));
  if (inserted) names.push_back(name);
  return it->second;
}

float triangle_area(const MeshData &m, size_t t) {
  const Vec3f &a = m.positions[m.indices[3 * t]], &b = m.positions[m.indices[3 * t + 1]],
              &c = m.positions[m.indices[3 * t + 2]];
  return 0.5f * length(cross(b - a, c - a));
}

}  // namespace

Expected<LightSet> LightSet::build(const SceneDesc &desc, GeometryScene &geo) {
  LightSet set;
  std::map<std::string, uint32_t> by_name;
  for (const LightDesc &ld : desc.lights) {
    Light l;
    l.kind = PointLight{ld.position, ld.intensity};
    l.power = 4 * kPi * luminance(ld.intensity);
    l.group = group_index(ld.group, set.count(), set.group_names_, by_name);
    set.lights_.push_back(std::move(l));
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
      if (a.triangles.empty()) continue;  // degenerate mesh: emits nothing, cannot be sampled
    }
    Light l;
    const float area = geo.shapes()[s].area;
    l.power = kPi * area * luminance(sd.emission) * (sd.two_sided ? 2 : 1);
    l.kind = std::move(a);
    l.group = group_index(sd.group, set.count(), set.group_names_, by_name);
    geo.shapes()[s].light_id = set.count();
    set.lights_.push_back(std::move(l));
  }
  return set;
}

}  // namespace nimbus
