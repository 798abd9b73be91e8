// The image I/O module (core/image_io.hpp): image files read through OpenImageIO.
#include <OpenImageIO/imageio.h>

#include <cstring>

#include "core/image_io.hpp"
#include "image_io/oiio_conversions.hpp"
#include "image_io/oiio_texture_cache.hpp"

namespace nimbus {
namespace {

class OiioImageFile final : public ImageFile {
 public:
  explicit OiioImageFile(std::unique_ptr<OIIO::ImageInput> in) : in_(std::move(in)) { describe(); }
  ~OiioImageFile() override {
    if (!in_->close()) (void)in_->geterror();  // OIIO complains at exit about unread errors
  }

  const ImageDesc &desc() const override { return desc_; }

  bool seek_part(int part) override {
    if (!in_->seek_subimage(part, 0)) {
      (void)in_->geterror();  // OIIO complains at exit about unread errors
      return false;
    }
    describe();
    return true;
  }

  bool read_rows(int y_begin, int y_end, PixelType type, void *out) override {
    const OIIO::ImageSpec &s = in_->spec();
    const int part = in_->current_subimage();
    // OpenImageIO reads no scanlines from tiled files.
    return s.tile_width > 0
               ? in_->read_tiles(part, 0, s.x, s.x + s.width, y_begin, y_end, s.z, s.z + 1, 0, s.nchannels,
                                 type_desc(type), out)
               : in_->read_scanlines(part, 0, y_begin, y_end, s.z, 0, s.nchannels, type_desc(type), out);
  }

  std::string error() override { return in_->geterror(); }

 private:
  void describe() { desc_ = desc_of(in_->spec()); }

  std::unique_ptr<OIIO::ImageInput> in_;
  ImageDesc desc_;
};

class OiioImageIo final : public ImageIo {
 public:
  Expected<std::unique_ptr<ImageFile>> open(const std::string &path) const override {
    auto in = OIIO::ImageInput::open(path);
    if (!in) return Error{OIIO::geterror()};
    return std::unique_ptr<ImageFile>(std::make_unique<OiioImageFile>(std::move(in)));
  }

  const TextureCache &textures() const override { return oiio_texture_cache(); }
};

}  // namespace
}  // namespace nimbus

extern "C" __attribute__((visibility("default"))) const nimbus::ImageIo *nimbus_image_io_entry(
    const char *host_version) {
  static const nimbus::OiioImageIo io;
  return std::strcmp(host_version, NIMBUS_VERSION_STRING) == 0 ? &io : nullptr;
}
