// The image I/O module (core/image_io.hpp): files read and written through OpenImageIO.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstring>

#include "core/image_io.hpp"
#include "image_io/oiio_conversions.hpp"
#include "image_io/oiio_texture_cache.hpp"

namespace nimbus {
namespace {

OIIO::ImageSpec spec_of(const ImageDesc &desc) {
  OIIO::ImageSpec spec(desc.width, desc.height, int(desc.channels.size()), type_desc(desc.type));
  spec.channelnames = desc.channels;
  // A channel named A is alpha, as in OpenImageIO's own default names (R, G, B, A).
  const auto alpha = std::find(desc.channels.begin(), desc.channels.end(), "A");
  spec.alpha_channel = alpha == desc.channels.end() ? -1 : int(alpha - desc.channels.begin());
  for (const ImageAttribute &a : desc.attributes) switch (a.kind) {
      case ImageAttribute::Kind::String:
        spec.attribute(a.name, a.text);
        break;
      case ImageAttribute::Kind::Int:
        spec.attribute(a.name, int(a.number));
        break;
      case ImageAttribute::Kind::Double:
        spec.attribute(a.name, OIIO::TypeDesc::DOUBLE, &a.number);
        break;
    }
  return spec;
}

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
  Status write(const std::string &format, const std::string &file,
               std::span<const ImagePart> parts) const override {
    auto out = OIIO::ImageOutput::create(format);
    if (!out) return Error{"OpenImageIO has no '" + format + "' writer: " + OIIO::geterror()};
    std::vector<OIIO::ImageSpec> specs;
    for (const ImagePart &part : parts) specs.push_back(spec_of(part.desc));
    // Every failure branch fetches the pending message: OIIO complains at exit about unread errors.
    const bool opened =
        specs.size() == 1 ? out->open(file, specs[0]) : out->open(file, int(specs.size()), specs.data());
    if (!opened) return Error{out->geterror()};
    for (size_t i = 0; i < parts.size(); ++i) {
      const bool written = (i == 0 || out->open(file, specs[i], OIIO::ImageOutput::AppendSubimage)) &&
                           out->write_image(specs[i].format, parts[i].pixels);
      if (!written) {
        const std::string reason = out->geterror();
        out->close();
        return Error{reason};
      }
    }
    if (!out->close()) return Error{out->geterror()};
    return Ok{};
  }

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
