// Film::write_exr: every active element in one multi-layer EXR.
#include <OpenImageIO/imageio.h>

#include <climits>
#include <cmath>

#include "film/atomic_file.hpp"
#include "film/film.hpp"
#include "film/image_write.hpp"

namespace nimbus {
namespace {

// Beauty is the unnamed layer (R, G, B) so every viewer shows it by default; other elements follow the
// "<layer>.<channel>" convention OpenEXR, OIIO and Nuke split layers by.
std::vector<std::string> channel_names(const std::string &layer, uint32_t channels) {
  const std::string prefix = layer.empty() ? "" : layer + ".";
  if (channels == 1) return {prefix + "Y"};
  return {prefix + "R", prefix + "G", prefix + "B"};
}

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

Status Film::write_exr(const std::string &path,
                       const std::vector<std::pair<std::string, std::string>> &string_meta,
                       const std::vector<std::pair<std::string, double>> &numeric_meta) const {
  const std::vector<int32_t> ids = active_elements();
  std::vector<std::string> names;
  for (int32_t id : ids) {
    for (std::string &n : channel_names(id == kBeauty ? "" : element_name(id), element_channels(id))) {
      names.push_back(std::move(n));
    }
  }
  const size_t total = names.size();

  // Interleave all elements into one float buffer: float, not half, because half saturates at 65504
  // and caustic highlights exceed that.
  std::vector<float> pixels(pixel_count() * total);
  size_t first = 0;
  for (int32_t id : ids) {
    const std::vector<float> image = resolve(id);
    const uint32_t c = element_channels(id);
    for (size_t p = 0; p < pixel_count(); ++p) {
      for (uint32_t k = 0; k < c; ++k) pixels[p * total + first + k] = image[p * c + k];
    }
    first += c;
  }

  OIIO::ImageSpec spec(static_cast<int>(width_), static_cast<int>(height_), static_cast<int>(total),
                       OIIO::TypeDesc::FLOAT);
  spec.channelnames = names;
  spec.alpha_channel = -1;
  spec.attribute("compression", "zip");
  spec.attribute("Software", "Nimbus " NIMBUS_VERSION_STRING);
  for (const auto &[key, value] : string_meta) spec.attribute("nimbus:" + key, value);
  for (const auto &[key, value] : numeric_meta) add_number(spec, "nimbus:" + key, value);

  return write_atomically(
      path, [&](const std::string &tmp) { return write_oiio_image("openexr", tmp, spec, pixels.data()); });
}

}  // namespace nimbus
