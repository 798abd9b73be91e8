// Film::write_exr: every active element in one multi-layer EXR; write_layered_exr: any layers, as one;
// both laid out by exr_layout.hpp.
#include "film/exr_layout.hpp"

#include <climits>
#include <cmath>

#include "core/image_io.hpp"
#include "film/atomic_file.hpp"
#include "film/exr_write.hpp"
#include "film/film.hpp"

namespace nimbus {
namespace {
ImageAttribute number_attribute(const std::string &name, double value) {
  // EXR has no 64-bit integer attribute: int32 covers counts, seeds and sizes, and a double holds any
  // larger count (up to 2^53) or fractional value exactly, where a float attribute would round.
  ImageAttribute a;
  a.name = name;
  a.number = value;
  const bool int32 =
      std::isfinite(value) && value == std::trunc(value) && value >= INT_MIN && value <= INT_MAX;
  a.kind = int32 ? ImageAttribute::Kind::Int : ImageAttribute::Kind::Double;
  return a;
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

  image.desc = image_desc(width, height, std::move(names), PixelType::Float);
  std::vector<ImageAttribute> &attributes = image.desc.attributes;
  attributes.push_back(text_attribute("compression", "zip"));
  attributes.push_back(text_attribute("Software", "Nimbus " NIMBUS_VERSION_STRING));
  for (const auto &[key, value] : string_meta) attributes.push_back(text_attribute("nimbus:" + key, value));
  for (const auto &[key, value] : numeric_meta)
    attributes.push_back(number_attribute("nimbus:" + key, value));
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
    const ImagePart part{image.desc, image.pixels.data()};
    return write_exr_file(tmp, {&part, 1});
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
