#include "materials/texture_set.hpp"

#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/texture.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/image_header.hpp"
#include "core/limits.hpp"

namespace nimbus {

namespace {

// How stored values become linear ones.
enum class Decode { None, Srgb, Gamma };

struct Texture {
  OIIO::TextureSystem::TextureHandle *handle = nullptr;
  int x = 0, y = 0;  // the data window's origin, for reading texels by index
  int width = 0, height = 0;
  int channels = 1;  // looked up: 1 (grey or data) or 3 (RGB)
  Decode decode = Decode::None;
  float gamma = 1;
};

Decode decode_of(const OIIO::ImageSpec &spec, TextureSet::Kind kind, float &gamma) {
  if (kind == TextureSet::Kind::Data || spec.format.is_floating_point()) return Decode::None;
  const std::string space = spec.get_string_attribute("oiio:ColorSpace");
  if (OIIO::Strutil::iequals(space, "linear") || OIIO::Strutil::iequals(space, "scene_linear"))
    return Decode::None;
  // PNG with a gAMA chunk other than sRGB's: a pure power law.
  gamma = spec.get_float_attribute("oiio:Gamma", 0);
  if (OIIO::Strutil::istarts_with(space, "gamma") && gamma > 0) return Decode::Gamma;
  return Decode::Srgb;  // PNG and JPEG say sRGB; integer files that say nothing are display images too
}

float decode_value(const Texture &tex, float v) {
  switch (tex.decode) {
    case Decode::Srgb:
      return srgb_to_linear(v);
    case Decode::Gamma:
      return std::pow(std::max(v, 0.0f), tex.gamma);
    case Decode::None:
      break;
  }
  return v;
}

// OIIO reports a failure as several lines, the first the cause and the rest how it surfaced (repeating the
// path and the cause); errors here are one line.
std::string first_line(const std::string &text) {
  std::string line = text.substr(0, text.find('\n'));
  while (!line.empty() && line.back() == ' ') line.pop_back();
  return line.empty() ? "unknown error" : line;
}

Error texture_error(const TextureDesc &t, const std::string &reason) {
  std::string message = t.path + ": cannot read texture: " + reason;
  if (t.where.line > 0)
    message = t.where.text() + ": error: " + (t.key.empty() ? "" : t.key + ": ") + message;
  return Error{std::move(message)};
}

// The operating system's reason a file cannot be read, which is clearer than the image library's ("could
// not open file"); empty when it can be opened.
std::string unreadable_reason(const std::string &path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return "is a directory";
  std::FILE *f = std::fopen(path.c_str(), "rb");
  if (!f) return std::strerror(errno);
  std::fclose(f);
  return {};
}

// One texture system for the process, created on first use and never destroyed. Private (with its own
// cache) so that these attributes stay away from the process-wide cache the rest of OpenImageIO uses
// (ImageBuf); never destroyed because OIIO 2.4's TextureSystem::destroy frees with a mismatched size
// (AddressSanitizer: new-delete-type-mismatch). Each TextureSet invalidates its files when done, which
// closes them and frees their tiles.
OIIO::TextureSystem &texture_system() {
  static OIIO::TextureSystem *const ts = [] {
    OIIO::TextureSystem *t = OIIO::TextureSystem::create(false, OIIO::ImageCache::create(false));
    t->attribute("max_memory_MB", 512.0f);
    t->attribute("autotile", 64);
    t->attribute("automip", 1);
    // Colour as stored, not multiplied by alpha: albedo ignores alpha.
    t->attribute("unassociatedalpha", 1);
    return t;
  }();
  return *ts;
}

}  // namespace

float srgb_to_linear(float encoded) {
  if (encoded <= 0.04045f) return encoded / 12.92f;
  return std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

struct TextureSet::Impl {
  OIIO::TextureSystem *ts = &texture_system();
  std::vector<Texture> textures;
  std::vector<OIIO::ustring> files;                      // each once, to invalidate
  std::map<std::tuple<std::string, Kind, int>, Id> ids;  // (path, kind, min_channels)

  ~Impl() {
    for (const OIIO::ustring &file : files) ts->invalidate(file);
  }

  // One lookup with zero derivatives: magnification filtering on the finest level. A progressive renderer
  // integrates the pixel footprint through pixel jitter, so no MIP filter width is needed.
  void fetch(const Texture &tex, OIIO::TextureOpt::InterpMode interp, float s, float t, float *out) const {
    OIIO::TextureOpt opt;
    opt.swrap = opt.twrap = OIIO::TextureOpt::WrapPeriodic;
    opt.interpmode = interp;
    if (!ts->texture(tex.handle, nullptr, opt, s, t, 0, 0, 0, 0, tex.channels, out)) {
      // Only an I/O failure after validation gets here (the file changed under us); drop the message so
      // that the per-thread error strings cannot grow without bound.
      (void)ts->geterror();
      for (int c = 0; c < tex.channels; ++c) out[c] = 0;
    }
  }

  // Filtered, linear texel values (tex.channels of them).
  void lookup(const Texture &tex, Vec2f st, float *out) const {
    if (tex.decode == Decode::None) return fetch(tex, OIIO::TextureOpt::InterpBilinear, st.x, st.y, out);
    // Decode before filtering (as GPUs do with sRGB formats): blending encoded values and decoding the
    // blend would darken every edge between texels. So the four texels are read and decoded one by one:
    // as one 2x2 block inside the image, by four nearest-texel lookups (which wrap) at its edges.
    const float x = st.x * float(tex.width) - 0.5f, y = st.y * float(tex.height) - 0.5f;
    const float x0 = std::floor(x), y0 = std::floor(y), fx = x - x0, fy = y - y0;
    const float bx = x0 - float(tex.width) * std::floor(x0 / float(tex.width));  // x0 wrapped into the image
    const float by = y0 - float(tex.height) * std::floor(y0 / float(tex.height));
    const int c_n = tex.channels;
    float texels[4 * 3];  // (0, 0), (1, 0), (0, 1), (1, 1), c_n channels each
    OIIO::TextureOpt opt;
    const bool inside = bx + 1 < float(tex.width) && by + 1 < float(tex.height);
    if (!inside ||
        !ts->get_texels(tex.handle, nullptr, opt, 0, tex.x + int(bx), tex.x + int(bx) + 2, tex.y + int(by),
                        tex.y + int(by) + 2, 0, 1, 0, c_n, OIIO::TypeDesc::FLOAT, texels)) {
      for (int k = 0; k < 4; ++k)
        fetch(tex, OIIO::TextureOpt::InterpClosest, (x0 + float(k & 1) + 0.5f) / float(tex.width),
              (y0 + float(k >> 1) + 0.5f) / float(tex.height), &texels[k * c_n]);
    }
    for (int c = 0; c < c_n; ++c) out[c] = 0;
    for (int k = 0; k < 4; ++k) {
      const float w = (k & 1 ? fx : 1 - fx) * (k >> 1 ? fy : 1 - fy);
      for (int c = 0; c < c_n; ++c) out[c] += w * decode_value(tex, texels[k * c_n + c]);
    }
  }

  // Reads every texel of the top level once, a band of rows at a time: truncated or corrupt pixel data is
  // found now, and the tiles read stay in the cache for the render.
  std::string read_all(const Texture &tex, const OIIO::ImageSpec &spec) const {
    OIIO::TextureOpt opt;
    constexpr int kRows = 64;
    std::vector<float> band(size_t(spec.width) * kRows * size_t(spec.nchannels));
    for (int y = spec.y; y < spec.y + spec.height; y += kRows) {
      const int y_end = std::min(y + kRows, spec.y + spec.height);
      if (!ts->get_texels(tex.handle, nullptr, opt, 0, spec.x, spec.x + spec.width, y, y_end, spec.z,
                          spec.z + std::max(spec.depth, 1), 0, spec.nchannels, OIIO::TypeDesc::FLOAT,
                          band.data()))
        return first_line(ts->geterror());
      for (float v : band)
        if (!std::isfinite(v)) return "contains NaN or infinite values";
    }
    return {};
  }
};

TextureSet::TextureSet() : impl_(std::make_unique<Impl>()) {}
TextureSet::~TextureSet() = default;

Expected<TextureSet::Id> TextureSet::add(const TextureDesc &desc, Kind kind, int min_channels) {
  if (auto found = impl_->ids.find({desc.path, kind, min_channels}); found != impl_->ids.end())
    return found->second;
  if (std::string reason = unreadable_reason(desc.path); !reason.empty()) return texture_error(desc, reason);
  if (auto problem = image_header_problem(desc.path)) return texture_error(desc, *problem);
  OIIO::TextureSystem &ts = *impl_->ts;
  const OIIO::ustring file(desc.path);
  if (std::find(impl_->files.begin(), impl_->files.end(), file) == impl_->files.end()) {
    // Read afresh: the cache outlives scenes, and the file may have changed since another scene read it.
    ts.invalidate(file);
    impl_->files.push_back(file);
  }
  Texture tex;
  tex.handle = ts.get_texture_handle(file, nullptr);
  OIIO::ImageSpec spec;
  if (!tex.handle || !ts.get_imagespec(tex.handle, nullptr, 0, spec))
    return texture_error(desc, first_line(ts.geterror()));
  if (spec.width < 1 || spec.height < 1 || spec.nchannels < 1)
    return texture_error(desc, "the image has no pixels");
  if (std::string big = oversized_input_image(spec.width, spec.height); !big.empty())
    return texture_error(desc, big);
  if (spec.depth > 1) return texture_error(desc, "volume images are not 2-D textures");
  if (spec.nchannels < min_channels)
    return texture_error(desc, "needs " + std::to_string(min_channels) + " channels, the image has " +
                                   std::to_string(spec.nchannels));
  tex.x = spec.x, tex.y = spec.y;
  tex.width = spec.width, tex.height = spec.height;
  tex.channels = kind == Kind::Color && spec.nchannels >= 3 ? 3 : (min_channels >= 3 ? 3 : 1);
  tex.decode = decode_of(spec, kind, tex.gamma);
  if (std::string reason = impl_->read_all(tex, spec); !reason.empty()) return texture_error(desc, reason);
  const auto id = Id(impl_->textures.size());
  impl_->textures.push_back(tex);
  impl_->ids.emplace(std::make_tuple(desc.path, kind, min_channels), id);
  return id;
}

Rgb TextureSet::rgb(Id id, Vec2f st) const {
  const Texture &tex = impl_->textures[id];
  float v[3];
  impl_->lookup(tex, st, v);
  return tex.channels >= 3 ? Rgb{v[0], v[1], v[2]} : Rgb(v[0]);
}

float TextureSet::scalar(Id id, Vec2f st) const {
  const Texture &tex = impl_->textures[id];
  float v[3];
  impl_->lookup(tex, st, v);
  return v[0];
}

}  // namespace nimbus
