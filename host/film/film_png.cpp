// Film::write_png: the beauty as a display-referred 8-bit preview; write_display_png: any RGB image, as one.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/image_io.hpp"
#include "film/atomic_file.hpp"
#include "film/display_transform.hpp"
#include "film/film.hpp"
#include "film/png_write.hpp"

namespace nimbus {

Status Film::write_png(const std::string &path, const std::string &ocio_config_path) const {
  return write_display_png(path, resolve(kBeauty), width_, height_, ocio_config_path);
}

Status write_display_png(const std::string &path, std::vector<float> rgb, uint32_t width, uint32_t height,
                         const std::string &ocio_config_path) {
  // Fail before touching the destination: a bad config must not cost the user an existing preview.
  if (Status shown = apply_display_transform(ocio_config_path, rgb, width, height); !shown) return shown;

  std::vector<uint8_t> bytes(rgb.size());
  for (size_t i = 0; i < rgb.size(); ++i) {
    // Display values above 1 are out of gamut for an 8-bit sRGB file; clip, and round to nearest.
    const float v = std::isnan(rgb[i]) ? 0.0f : std::clamp(rgb[i], 0.0f, 1.0f);
    bytes[i] = static_cast<uint8_t>(std::lround(v * 255.0f));
  }
  ImagePart png{image_desc(width, height, {"R", "G", "B"}, PixelType::UInt8), bytes.data()};
  png.desc.attributes.push_back(text_attribute("Software", "Nimbus " NIMBUS_VERSION_STRING));
  return write_atomically(path, [&](const std::string &tmp) { return write_png_file(tmp, png); });
}

}  // namespace nimbus
