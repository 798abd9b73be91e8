// Everything a render reads: the built scene, the film and the loop's shared flags. The host's C
// services (abi/) forward to it; it knows nothing of plugins.
#pragma once

#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <tbb/task_arena.h>

#include "core/expected.hpp"
#include "film/film.hpp"
#include "geometry/geometry_scene.hpp"
#include "lights/light_set.hpp"
#include "materials/bsdf.hpp"
#include "materials/textured_materials.hpp"
#include "render/camera.hpp"
#include "render/error_estimate.hpp"
#include "render/pixel_filter.hpp"
#include "scene/scene_desc.hpp"

namespace nimbus {

using LogFn = std::function<void(int level, const std::string &plugin_id, const std::string &msg)>;

struct RenderContext {
  const SceneDesc *desc = nullptr;
  std::unique_ptr<GeometryScene> geometry;
  LightSet lights;
  std::vector<Bsdf> bsdfs;                      // one per scene material
  std::unique_ptr<TexturedMaterials> textures;  // null unless a material reads a texture
  Camera camera;
  PixelFilter filter;
  std::unique_ptr<Film> film;
  // Only with a target error: odd-iteration beauty, for the reference-free error estimate.
  std::unique_ptr<ErrorEstimate> error_estimate;
  uint64_t iteration = 0;  // the iteration being rendered (1-based), set before its tiles start
  uint64_t seed = 1;
  // Film element of each LightMix group (empty when LightMix was not requested).
  std::vector<int32_t> lightmix_elements;

  std::unique_ptr<tbb::task_arena> arena;
  uint32_t worker_count = 1;
  std::thread::id main_thread;
  std::atomic<bool> *cancel = nullptr;  // set by Ctrl-C or the time budget; owned by the caller
  LogFn log;

  // Rays traced, per worker (cache-line padded so counting costs no contention); summed after the render.
  struct alignas(64) RayCounter {
    uint64_t rays = 0;
  };
  std::vector<RayCounter> ray_counters;
  uint64_t rays_traced() const {
    uint64_t n = 0;
    for (const RayCounter &c : ray_counters) n += c.rays;
    return n;
  }

  // Statistics plugins add through the progress service (written into the EXR metadata).
  std::mutex stats_mutex;
  std::map<std::string, double> stats;
  // The phase a plugin reports (shown by the progress display).
  std::mutex phase_mutex;
  std::string phase;
  uint64_t phase_done = 0, phase_total = 0;

  // Builds geometry, lights, materials and camera for `desc` (which must outlive the context).
  static Expected<std::unique_ptr<RenderContext>> build(const SceneDesc &desc, uint32_t threads);
};

}  // namespace nimbus
