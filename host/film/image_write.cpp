#include "film/image_write.hpp"

namespace nimbus {

Status write_image_file(const std::string &format, const std::string &file,
                        std::span<const ImagePart> parts) {
  const Expected<const ImageIo *> io = image_io();
  if (!io) return io.error();
  return (*io)->write(format, file, parts);
}

ImageDesc image_desc(uint32_t width, uint32_t height, std::vector<std::string> channels, PixelType type) {
  ImageDesc desc;
  desc.width = int(width), desc.height = int(height);
  desc.channels = std::move(channels);
  desc.type = type;
  return desc;
}

ImageAttribute text_attribute(std::string name, std::string text) {
  ImageAttribute a;
  a.name = std::move(name);
  a.text = std::move(text);
  return a;
}

}  // namespace nimbus
