// The image reader of `nimbus compare` and `nimbus lightmix` (film/image_read.hpp, through OpenImageIO):
// the input is image.png when it starts with the PNG signature, else image.exr. Every refusal must be one
// line naming the path. An image read is then compared with itself as `nimbus compare` would, which must
// succeed for any layer it holds. An EXR is also read as `nimbus merge` reads a task's partial EXR
// (film/partial_exr.hpp): refused in one line naming the path, or sums of the image's size.
#include <cstdint>
#include <cstring>
#include <string>

#include "film/image_compare.hpp"
#include "film/image_read.hpp"
#include "film/partial_exr.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  using namespace nimbus::fuzz;
  const bool png = size >= 8 && std::memcmp(data, "\x89PNG\r\n\x1a\n", 8) == 0;
  const std::string path = (scratch_dir() / (png ? "image.png" : "image.exr")).string();
  write_file(path, std::string_view(reinterpret_cast<const char *>(data), size));

  if (!png) {
    const nimbus::Expected<nimbus::PartialImage> part = nimbus::read_partial_exr(path);
    if (!part) {
      check_error_line(part.error().message, path);
    } else {
      for (const nimbus::PartialElement &e : part->elements)
        require(
            e.sums.size() == size_t(part->width) * part->height * e.channels,
            "partial element " + e.name + " holds " + std::to_string(e.sums.size()) + " sums for its size");
    }
  }
  const nimbus::Expected<nimbus::ImageLayers> image = nimbus::read_exr_layers(path);
  if (!image) {
    check_error_line(image.error().message, path);
    return 0;
  }
  for (const auto &[name, layer] : image->layers) {
    require(layer.data.size() == size_t(image->width) * image->height * layer.channel_names.size(),
            "layer " + name + " holds " + std::to_string(layer.data.size()) + " values for its size");
    const auto metrics = nimbus::compare_images(layer, layer, image->width, image->height);
    require(metrics.ok(), "layer " + name + " cannot be compared with itself");
  }
  return 0;
}
