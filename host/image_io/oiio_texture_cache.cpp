#include "image_io/oiio_texture_cache.hpp"

#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/texture.h>

#include "image_io/oiio_conversions.hpp"

namespace nimbus {
namespace {

class OiioTextureCache final : public TextureCache {
 public:
  // Private (with its own cache) so that these attributes stay away from the process-wide cache the rest
  // of OpenImageIO uses (ImageBuf); never destroyed because OIIO 2.4's TextureSystem::destroy frees with a
  // mismatched size (AddressSanitizer: new-delete-type-mismatch).
  OiioTextureCache() : ts_(OIIO::TextureSystem::create(false, OIIO::ImageCache::create(false))) {
    ts_->attribute("max_memory_MB", 512.0f);
    ts_->attribute("autotile", 64);
    ts_->attribute("automip", 1);
    // Colour as stored, not multiplied by alpha: albedo ignores alpha.
    ts_->attribute("unassociatedalpha", 1);
  }

  Expected<std::pair<Handle, ImageDesc>> open(const std::string &path) const override {
    OIIO::TextureSystem::TextureHandle *handle = ts_->get_texture_handle(OIIO::ustring(path), nullptr);
    OIIO::ImageSpec spec;
    if (!handle || !ts_->get_imagespec(handle, nullptr, 0, spec)) return Error{ts_->geterror()};
    return std::pair<Handle, ImageDesc>{handle, desc_of(spec)};
  }

  void invalidate(const std::string &path) const override { ts_->invalidate(OIIO::ustring(path)); }

  bool lookup(Handle file, bool nearest, float s, float t, int channels, float *out) const override {
    OIIO::TextureOpt opt;
    opt.swrap = opt.twrap = OIIO::TextureOpt::WrapPeriodic;
    opt.interpmode = nearest ? OIIO::TextureOpt::InterpClosest : OIIO::TextureOpt::InterpBilinear;
    if (ts_->texture(static_cast<OIIO::TextureSystem::TextureHandle *>(file), nullptr, opt, s, t, 0, 0, 0, 0,
                     channels, out))
      return true;
    // Drop the message so that the per-thread error strings cannot grow without bound.
    (void)ts_->geterror();
    return false;
  }

  bool texels(Handle file, int x0, int x1, int y0, int y1, int z0, int z1, int channels,
              float *out) const override {
    OIIO::TextureOpt opt;
    return ts_->get_texels(static_cast<OIIO::TextureSystem::TextureHandle *>(file), nullptr, opt, 0, x0, x1,
                           y0, y1, z0, z1, 0, channels, OIIO::TypeDesc::FLOAT, out);
  }

  std::string error() const override { return ts_->geterror(); }

 private:
  OIIO::TextureSystem *const ts_;
};

}  // namespace

const TextureCache &oiio_texture_cache() {
  static const OiioTextureCache *const cache = new OiioTextureCache;
  return *cache;
}

}  // namespace nimbus
