#include "lightmix_fixture.hpp"

#include <random>

#include "film/film.hpp"

namespace nimbus::test {

LightMixImage make_lightmix_image() {
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  LightMixImage img;
  const size_t n = size_t(kWidth) * kHeight;
  for (size_t i = 0; i < n * 3; ++i) {
    img.key.push_back(u(rng) * 4);
    img.fill.push_back(u(rng) * 0.5f);
    img.beauty.push_back(img.key.back() + img.fill.back() + u(rng) * 1e-3f);
    img.albedo.push_back(u(rng));
  }
  for (size_t i = 0; i < n; ++i) img.depth.push_back(u(rng) * 10);
  return img;
}

Status write_lightmix_exr(const std::string &path, const LightMixImage &img, bool with_lightmix) {
  std::vector<ExrLayer> layers = {{{"R", "G", "B"}, img.beauty.data()},
                                  {{"albedo.R", "albedo.G", "albedo.B"}, img.albedo.data()},
                                  {{"depth.Y"}, img.depth.data()}};
  if (with_lightmix) {
    layers.push_back({{"lightmix.key.R", "lightmix.key.G", "lightmix.key.B"}, img.key.data()});
    layers.push_back({{"lightmix.fill.R", "lightmix.fill.G", "lightmix.fill.B"}, img.fill.data()});
  }
  return write_layered_exr(path, kWidth, kHeight, layers, {{"scene", "synthetic.yaml"}},
                           {{"iterations", 16}});
}

}  // namespace nimbus::test
