#include "world/world.hpp"

#include <algorithm>

#include "core/rgb_uplift_table.hpp"

namespace nimbus {

Expected<std::unique_ptr<World>> World::build(const SceneDesc &desc, FilterType filter) {
  auto world = std::make_unique<World>();
  auto geo = GeometryScene::build(desc);
  if (!geo) return geo.error();
  world->geometry = std::move(geo.value());
  auto lights = LightSet::build(desc, *world->geometry);
  if (!lights) return lights.error();
  world->lights = std::move(lights.value());
  for (const MaterialDesc &m : desc.materials) world->bsdfs.push_back(make_bsdf(m));
  auto textures = TexturedMaterials::build(desc.materials);
  if (!textures) return textures.error();
  world->textures = std::move(textures.value());
  if (std::any_of(desc.materials.begin(), desc.materials.end(),
                  [](const MaterialDesc &m) { return m.dispersive(); })) {
    for (const MaterialDesc &m : desc.materials)
      world->dispersion.push_back(m.dispersive() ? m.dispersion : std::nullopt);
    // Built now (0.3 s, once per process) rather than by the first render thread to uplift a colour.
    srgb_uplift_table();
  }
  world->sharp_objects = find_sharp_objects(desc, *world->geometry, world->bsdfs);
  world->camera = Camera(desc.camera, desc.render.width, desc.render.height);
  world->shutter = desc.camera.shutter;
  world->moving_objects = find_moving_objects(*world->geometry, world->shutter.instantaneous());
  world->filter = PixelFilter(filter);
  return world;
}

}  // namespace nimbus
