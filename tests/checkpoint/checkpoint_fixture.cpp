#include "checkpoint_fixture.hpp"

#include <bit>
#include <cmath>
#include <limits>
#include <random>

namespace nimbus::test {

std::unique_ptr<Film> make_film(const std::vector<std::string> &requested, uint32_t width, uint32_t height) {
  auto film = std::make_unique<Film>(width, height);
  film->register_element("albedo", 3, Film::kAverage);
  film->register_element("depth", 1, Film::kAverage);
  film->register_element("lightmix.key", 3, Film::kSplat);
  film->register_element("normal", 3, Film::kAverage);
  for (const std::string &name : requested) film->request(name);
  if (!film->allocate().ok()) return nullptr;
  film->set_worker_count(3);
  return film;
}

void add_iteration(Film &film, uint64_t iteration) {
  std::mt19937 rng(static_cast<uint32_t>(iteration));
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::uniform_int_distribution<int> octave(-12, 12);
  auto value = [&] { return std::ldexp(unit(rng), octave(rng)); };
  const auto ids = film.active_elements();
  for (uint32_t y = 0; y < film.height(); ++y) {
    for (uint32_t x = 0; x < film.width(); ++x) {
      for (int32_t id : ids) {
        float v[3] = {value(), value(), value()};
        if (film.element_name(id) == "lightmix.key") {
          const uint32_t worker = (x + y) % 3;
          film.splat(worker, id, unit(rng) * float(film.width()), unit(rng) * float(film.height()), v);
        } else {
          if (iteration == 1 && x == 1 && y == 1 && id == Film::kBeauty)
            v[1] = std::numeric_limits<float>::quiet_NaN();
          film.accumulate(id, x, y, v);
        }
      }
    }
  }
  film.merge_splats();
  film.end_iteration();
}

CheckpointInfo make_info() {
  CheckpointInfo info;
  info.seed = 0xfedcba9876543210ULL;  // above 2^63: the full 64 bits must survive
  info.integrator = "nimbus.pt";
  info.fingerprint =
      "scene_hash=0123456789abcdef\nresolution=7x5\nseed=18364758544493064720\nelements=albedo\n";
  info.seconds = 12.345678901234;
  return info;
}

std::vector<uint64_t> sum_bits(const Film &film, const std::string &element) {
  for (int32_t id : film.active_elements()) {
    if (film.element_name(id) != element) continue;
    std::vector<uint64_t> bits;
    for (double v : film.sums(id)) bits.push_back(std::bit_cast<uint64_t>(v));
    return bits;
  }
  return {};
}

}  // namespace nimbus::test
