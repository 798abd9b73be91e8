// Film::write_exr: every active element in one multi-layer EXR; write_layered_exr: any layers, as one;
// both laid out by exr_layout.hpp.
#include "film/exr_layout.hpp"

#include <climits>
#include <cmath>

#include "film/atomic_file.hpp"
#include "film/film.hpp"
#include "film/image_write.hpp"

namespace nimbus {
namespace {
void add_number(OIIO::ImageSpec &spec, const std::string &name, double value) {
  // EXR has no 64-bit integer attribute: int32 covers counts, seeds and sizes, and a double holds any
  // larger count (up to 2^53) or fractional value exactly, where a float attribute would round.
  if (std::isfinite(value) && value == std::trunc(value) && value >= INT_MIN && value <= INT_MAX) {
    spec.attribute(name, static_cast<int>(value));
  } else {
    spec.attribute(name, OIIO::TypeDesc::DOUBLE, &value);
  }
}

}  // namespace

std::vector<std::string> exr_channel_names(const std::string &layer, uint32_t channels) {
  const std::string prefix = layer.empty() ? "" : layer + ".";
  if (channels == 1) return {prefix + "Y"};
  return {prefix + "R", prefix + "G", prefix + "B"};
}

ExrImage layered_exr_image(uint32_t width, uint32_t height, const std::vector<ExrLayer> &layers,
                           const std::vector<std::pair<std::string, std::string>> &string_meta,
                           const std::vector<std::pair<std::string, double>> &numeric_meta) {
  std::vector<std::string> names;
  for (const ExrLayer &layer : layers)
    names.insert(names.end(), layer.channel_names.begin(), layer.channel_names.end());
  const size_t total = names.size();
  const size_t pixel_count = size_t(width) * height;

  // Interleave all layers into one float buffer: float, not half, because half saturates at 65504
  // and caustic highlights exceed that.
  ExrImage image;
  image.pixels.resize(pixel_count * total);
  size_t first = 0;
  for (const ExrLayer &layer : layers) {
    const size_t c = layer.channel_names.size();
    for (size_t p = 0; p < pixel_count; ++p) {
      for (size_t k = 0; k < c; ++k) image.pixels[p * total + first + k] = layer.pixels[p * c + k];
    }
    first += c;
  }

  OIIO::ImageSpec &spec = image.spec;
  spec = OIIO::ImageSpec(static_cast<int>(width), static_cast<int>(height), static_cast<int>(total),
                         OIIO::TypeDesc::FLOAT);
  spec.channelnames = names;
  spec.alpha_channel = -1;
  spec.attribute("compression", "zip");
  spec.attribute("Software", "Nimbus " NIMBUS_VERSION_STRING);
  for (const auto &[key, value] : string_meta) spec.attribute("nimbus:" + key, value);
  for (const auto &[key, value] : numeric_meta) add_number(spec, "nimbus:" + key, value);
  return image;
}

ExrImage film_exr_image(const Film &film, const std::vector<std::pair<std::string, std::string>> &string_meta,
                        const std::vector<std::pair<std::string, double>> &numeric_meta) {
  const std::vector<int32_t> ids = film.active_elements();
  std::vector<std::vector<float>> images;
  std::vector<ExrLayer> layers;
  images.reserve(ids.size());
  for (int32_t id : ids) {
    images.push_back(film.resolve(id));
    layers.push_back(
        {exr_channel_names(id == Film::kBeauty ? "" : film.element_name(id), film.element_channels(id)),
         images.back().data()});
  }
  return layered_exr_image(film.width(), film.height(), layers, string_meta, numeric_meta);
}

Status write_exr_image(const std::string &path, const ExrImage &image) {
  return write_atomically(path, [&](const std::string &tmp) {
    return write_oiio_image("openexr", tmp, image.spec, image.pixels.data());
  });
}

Status Film::write_exr(const std::string &path,
                       const std::vector<std::pair<std::string, std::string>> &string_meta,
                       const std::vector<std::pair<std::string, double>> &numeric_meta) const {
  return write_exr_image(path, film_exr_image(*this, string_meta, numeric_meta));
}

Status write_layered_exr(const std::string &path, uint32_t width, uint32_t height,
                         const std::vector<ExrLayer> &layers,
                         const std::vector<std::pair<std::string, std::string>> &string_meta,
                         const std::vector<std::pair<std::string, double>> &numeric_meta) {
  return write_exr_image(path, layered_exr_image(width, height, layers, string_meta, numeric_meta));
}

}  // namespace nimbus
