// Image textures for materials, read through OpenImageIO's TextureSystem: tiles are cached (bounded memory,
// shared by all render threads; the system lives for the process, each set releases its files when it
// dies) and untiled, un-MIP-mapped files are tiled and MIP-mapped on demand. Every file is opened and read
// once when added, so a missing, unreadable or truncated texture is an error at scene build, never a
// silent black surface halfway through a render.
#pragma once

#include <cstdint>
#include <memory>

#include <nimbus/cpp/math.hpp>
#include "core/expected.hpp"
#include "scene/scene_desc.hpp"

namespace nimbus {

class TextureSet {
 public:
  using Id = uint32_t;

  // What the texels mean. Colour from an integer file (PNG, JPEG: 8 or 16 bits) is sRGB-encoded unless the
  // file says otherwise, and is decoded to linear; data (roughness, normals) is used as stored.
  enum class Kind { Color, Data };

  TextureSet();
  ~TextureSet();
  TextureSet(const TextureSet &) = delete;
  TextureSet &operator=(const TextureSet &) = delete;

  // Opens and validates `texture`; at least `min_channels` channels are required. On failure the message
  // reads "SCENE:LINE:COLUMN: error: KEY: PATH: cannot read texture: REASON". A file added twice with the
  // same kind is one texture.
  Expected<Id> add(const TextureDesc &texture, Kind kind, int min_channels = 1);

  // Bilinear lookup at texture coordinates (s, t) with OpenImageIO's orientation (t = 0 is the top row,
  // texel centres at (i + 1/2) / size), wrapping periodically; sRGB texels are decoded before they are
  // blended. Colour is linear; one-channel files give grey. Safe to call from any number of threads.
  Rgb rgb(Id id, Vec2f st) const;
  // The first channel.
  float scalar(Id id, Vec2f st) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// sRGB transfer function, encoded [0, 1] -> linear (IEC 61966-2-1).
float srgb_to_linear(float encoded);

}  // namespace nimbus
