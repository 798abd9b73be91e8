#include "materials/texture_set.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include "core/image_header.hpp"
#include "core/image_io.hpp"
#include "core/limits.hpp"

namespace nimbus {

namespace {

// How stored values become linear ones.
enum class Decode { None, Srgb, Gamma };

struct Texture {
  TextureCache::Handle handle = nullptr;
  int x = 0, y = 0;  // the data window's origin, for reading texels by index
  int width = 0, height = 0;
  int channels = 1;  // looked up: 1 (grey or data) or 3 (RGB)
  Decode decode = Decode::None;
  float gamma = 1;
};

bool equals_ignoring_case(std::string_view a, std::string_view b) {
  return std::ranges::equal(a, b, [](char x, char y) { return std::tolower(x) == std::tolower(y); });
}

Decode decode_of(const ImageDesc &desc, TextureSet::Kind kind, float &gamma) {
  if (kind == TextureSet::Kind::Data || desc.floating_point) return Decode::None;
  const ImageAttribute *colour_space = desc.find("oiio:ColorSpace");
  const std::string space = colour_space ? colour_space->text : std::string();
  if (equals_ignoring_case(space, "linear") || equals_ignoring_case(space, "scene_linear"))
    return Decode::None;
  // PNG with a gAMA chunk other than sRGB's: a pure power law.
  const ImageAttribute *g = desc.find("oiio:Gamma");
  gamma = g && g->kind != ImageAttribute::Kind::String ? float(g->number) : 0.0f;
  if (equals_ignoring_case(space.substr(0, 5), "gamma") && gamma > 0) return Decode::Gamma;
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

}  // namespace

float srgb_to_linear(float encoded) {
  if (encoded <= 0.04045f) return encoded / 12.92f;
  return std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

struct TextureSet::Impl {
  const TextureCache *cache = nullptr;  // the image I/O module's, from the first add
  std::vector<Texture> textures;
  std::vector<std::string> files;                        // each once, to invalidate
  std::map<std::tuple<std::string, Kind, int>, Id> ids;  // (path, kind, min_channels)

  ~Impl() {
    for (const std::string &file : files) cache->invalidate(file);
  }

  // One lookup with zero derivatives: magnification filtering on the finest level. A progressive renderer
  // integrates the pixel footprint through pixel jitter, so no MIP filter width is needed.
  void fetch(const Texture &tex, bool nearest, float s, float t, float *out) const {
    // Only an I/O failure after validation fails here (the file changed under us).
    if (!cache->lookup(tex.handle, nearest, s, t, tex.channels, out))
      for (int c = 0; c < tex.channels; ++c) out[c] = 0;
  }

  // Filtered, linear texel values (tex.channels of them).
  void lookup(const Texture &tex, Vec2f st, float *out) const {
    if (tex.decode == Decode::None) return fetch(tex, false, st.x, st.y, out);
    // Decode before filtering (as GPUs do with sRGB formats): blending encoded values and decoding the
    // blend would darken every edge between texels. So the four texels are read and decoded one by one:
    // as one 2x2 block inside the image, by four nearest-texel lookups (which wrap) at its edges.
    const float x = st.x * float(tex.width) - 0.5f, y = st.y * float(tex.height) - 0.5f;
    const float x0 = std::floor(x), y0 = std::floor(y), fx = x - x0, fy = y - y0;
    const float bx = x0 - float(tex.width) * std::floor(x0 / float(tex.width));  // x0 wrapped into the image
    const float by = y0 - float(tex.height) * std::floor(y0 / float(tex.height));
    const int c_n = tex.channels;
    float texels[4 * 3];  // (0, 0), (1, 0), (0, 1), (1, 1), c_n channels each
    const bool inside = bx + 1 < float(tex.width) && by + 1 < float(tex.height);
    const bool read = inside && cache->texels(tex.handle, tex.x + int(bx), tex.x + int(bx) + 2,
                                              tex.y + int(by), tex.y + int(by) + 2, 0, 1, c_n, texels);
    // A failed read inside the image (the file changed under us) drops its message, so that the
    // per-thread error strings cannot grow without bound.
    if (inside && !read) (void)cache->error();
    if (!read) {
      for (int k = 0; k < 4; ++k)
        fetch(tex, true, (x0 + float(k & 1) + 0.5f) / float(tex.width),
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
  std::string read_all(const Texture &tex, const ImageDesc &desc) const {
    constexpr int kRows = 64;
    const int channels = int(desc.channels.size());
    std::vector<float> band(size_t(desc.width) * kRows * size_t(channels));
    for (int y = desc.y; y < desc.y + desc.height; y += kRows) {
      const int y_end = std::min(y + kRows, desc.y + desc.height);
      if (!cache->texels(tex.handle, desc.x, desc.x + desc.width, y, y_end, desc.z,
                         desc.z + std::max(desc.depth, 1), channels, band.data()))
        return first_line(cache->error());
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
  if (!impl_->cache) {
    const Expected<const ImageIo *> io = image_io();
    if (!io) return texture_error(desc, io.error().message);
    impl_->cache = &(*io)->textures();
  }
  const TextureCache &cache = *impl_->cache;
  if (std::find(impl_->files.begin(), impl_->files.end(), desc.path) == impl_->files.end()) {
    // Read afresh: the cache outlives scenes, and the file may have changed since another scene read it.
    cache.invalidate(desc.path);
    impl_->files.push_back(desc.path);
  }
  Texture tex;
  auto opened = cache.open(desc.path);
  if (!opened) return texture_error(desc, first_line(opened.error().message));
  tex.handle = opened->first;
  const ImageDesc &spec = opened->second;
  const int channels = int(spec.channels.size());
  if (spec.width < 1 || spec.height < 1 || channels < 1)
    return texture_error(desc, "the image has no pixels");
  if (std::string big = oversized_input_image(spec.width, spec.height); !big.empty())
    return texture_error(desc, big);
  if (spec.depth > 1) return texture_error(desc, "volume images are not 2-D textures");
  if (channels < min_channels)
    return texture_error(desc, "needs " + std::to_string(min_channels) + " channels, the image has " +
                                   std::to_string(channels));
  tex.x = spec.x, tex.y = spec.y;
  tex.width = spec.width, tex.height = spec.height;
  tex.channels = kind == Kind::Color && channels >= 3 ? 3 : (min_channels >= 3 ? 3 : 1);
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
