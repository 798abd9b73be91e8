// org.example.eyelight: "eye light" shading, a light at the camera: each pixel's first surface, its
// albedo times the cosine between the view ray and the surface normal. Shows the C++ wrapper: the
// base class fills the C tables, catches exceptions and recovers `this` for every hook.
#include <nimbus/nimbus.hpp>

#include <cmath>

namespace example {

const char *const kRequired[] = {"nimbus.host.scene-query@1", "nimbus.host.camera@1", "nimbus.host.bsdf@1",
                                 "nimbus.host.film@1", nullptr};

class EyeLight final : public nimbus::sdk::Integrator {
 public:
  NIMBUS_DESCRIPTOR("org.example.eyelight", "Example: eye light (C++)", "Example Inc.",
                    NIMBUS_KIND_INTEGRATOR, 1, 0, 0, nullptr, kRequired)

  nimbus_status_t init() override {
    scene_ = host().service<nimbus_host_scene_query_v1_t>(NIMBUS_SERVICE_SCENE_QUERY);
    camera_ = host().service<nimbus_host_camera_v1_t>(NIMBUS_SERVICE_CAMERA);
    bsdf_ = host().service<nimbus_host_bsdf_v1_t>(NIMBUS_SERVICE_BSDF);
    film_ = host().service<nimbus_host_film_v1_t>(NIMBUS_SERVICE_FILM);
    return scene_ && camera_ && bsdf_ && film_ ? NIMBUS_OK : NIMBUS_E_UNSUPPORTED;
  }

  nimbus_status_t render_tile(const nimbus_thread_ctx_t &ctx, const nimbus_tile_t &tile) override {
    for (uint32_t y = tile.y0; y < tile.y1; ++y)
      for (uint32_t x = tile.x0; x < tile.x1; ++x) {
        float rgb[3] = {0, 0, 0};
        shade(ctx, x, y, rgb);
        film_->accumulate(host().get(), &ctx, NIMBUS_ELEMENT_BEAUTY, x, y, rgb);
      }
    return NIMBUS_OK;
  }

 private:
  void shade(const nimbus_thread_ctx_t &ctx, uint32_t x, uint32_t y, float rgb[3]) const {
    const nimbus_host_t *h = host().get();
    const nimbus_camera_sample_t cs{{float(x) + 0.5f, float(y) + 0.5f}, {0.5f, 0.5f}};
    nimbus_ray_t ray;
    if (!(camera_->generate_ray(h, &cs, &ray) > 0)) return;
    nimbus_hit_t hit;
    scene_->intersect(h, &ctx, &ray, &hit, 1);
    if (hit.geom_id == NIMBUS_NONE) return;
    nimbus_interaction_t ix;
    scene_->interaction(h, &ray, &hit, &ix);
    const float wo[3] = {-ray.dir[0], -ray.dir[1], -ray.dir[2]};
    const float cosine = std::fabs(wo[0] * ix.ns[0] + wo[1] * ix.ns[1] + wo[2] * ix.ns[2]);
    bsdf_->albedo(h, &ix, wo, rgb);
    for (int c = 0; c < 3; ++c) rgb[c] *= cosine;
  }

  const nimbus_host_scene_query_v1_t *scene_ = nullptr;
  const nimbus_host_camera_v1_t *camera_ = nullptr;
  const nimbus_host_bsdf_v1_t *bsdf_ = nullptr;
  const nimbus_host_film_v1_t *film_ = nullptr;
};

}  // namespace example

NIMBUS_PLUGIN_LIBRARY(example::EyeLight)
