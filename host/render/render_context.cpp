#include "render/render_context.hpp"

namespace nimbus {

Expected<std::unique_ptr<RenderContext>> RenderContext::build(const SceneDesc &desc, uint32_t threads) {
  auto ctx = std::make_unique<RenderContext>();
  ctx->desc = &desc;
  ctx->seed = desc.render.seed;
  auto geo = GeometryScene::build(desc);
  if (!geo) return geo.error();
  ctx->geometry = std::move(geo.value());
  auto lights = LightSet::build(desc, *ctx->geometry);
  if (!lights) return lights.error();
  ctx->lights = std::move(lights.value());
  for (const MaterialDesc &m : desc.materials) ctx->bsdfs.push_back(make_bsdf(m));
  auto textures = TexturedMaterials::build(desc.materials);
  if (!textures) return textures.error();
  ctx->textures = std::move(textures.value());
  ctx->camera = Camera(desc.camera, desc.render.width, desc.render.height);
  const std::string &f = desc.render.filter;
  if (f == "box") {
    ctx->filter = PixelFilter(FilterType::Box);
  } else if (f == "gaussian") {
    ctx->filter = PixelFilter(FilterType::Gaussian);
  } else if (f == "blackman-harris") {
    ctx->filter = PixelFilter(FilterType::BlackmanHarris);
  } else {
    return Error{desc.path + ": unknown pixel filter '" + f + "' (known: box, gaussian, blackman-harris)"};
  }
  ctx->film = std::make_unique<Film>(desc.render.width, desc.render.height);
  const int n = threads > 0 ? int(threads) : tbb::this_task_arena::max_concurrency();
  ctx->arena = std::make_unique<tbb::task_arena>(n);
  ctx->worker_count = uint32_t(n);
  ctx->ray_counters.resize(size_t(n));
  ctx->main_thread = std::this_thread::get_id();
  return ctx;
}

}  // namespace nimbus
