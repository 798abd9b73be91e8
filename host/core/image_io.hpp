// Image files read through OpenImageIO (textures, environment maps, EXRs back), which lives in a module of
// its own (lib/nimbus/host/libnimbus_image_io.so) that the host loads when it first reads one: OpenImageIO
// links ~260 libraries whose loading and relocation take 0.2 s, which every command and test process would
// otherwise pay at start-up. The film writes its EXRs and PNGs with OpenEXR and libpng directly
// (film/exr_write.hpp, film/png_write.hpp), from the records below. The interface is internal to the host
// (C++, built with it), not the plugin ABI.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/expected.hpp"

namespace nimbus {

// Pixel values as they cross the interface (a file may store another type: OpenImageIO converts).
enum class PixelType : uint8_t { UInt8, UInt32, Float };

// A header attribute. Written: a string, an int32 or a double; read: strings, and every scalar number
// (any integer width, half, float, double) as a Double holding it exactly up to 2^53.
struct ImageAttribute {
  enum class Kind : uint8_t { String, Int, Double };
  std::string name;
  Kind kind = Kind::String;
  std::string text;   // Kind::String
  double number = 0;  // Kind::Int and Kind::Double
};

// One image of a file (one part of a multi-part EXR).
struct ImageDesc {
  int x = 0, y = 0, z = 0;  // the data window's origin (read; written images start at 0)
  int width = 0, height = 0, depth = 1;
  int tile_width = 0, tile_height = 0;  // read: 0 for scanline files
  std::vector<std::string> channels;    // one name per channel
  PixelType type = PixelType::Float;    // written: the file's pixel type
  bool floating_point = false;          // read: the file stores floating-point values
  std::vector<ImageAttribute> attributes;

  // The attribute called `name`, or null.
  const ImageAttribute *find(const std::string &name) const {
    for (const ImageAttribute &a : attributes)
      if (a.name == name) return &a;
    return nullptr;
  }
};

// An image description of `width` x `height` pixels with these channels.
inline ImageDesc image_desc(uint32_t width, uint32_t height, std::vector<std::string> channels,
                            PixelType type) {
  ImageDesc desc;
  desc.width = int(width), desc.height = int(height);
  desc.channels = std::move(channels);
  desc.type = type;
  return desc;
}

// A string attribute.
inline ImageAttribute text_attribute(std::string name, std::string text) {
  ImageAttribute a;
  a.name = std::move(name);
  a.text = std::move(text);
  return a;
}

// An image to write: `pixels` holds desc.channels.size() values of desc.type per pixel, interleaved,
// scanlines top down. Borrowed for the call.
struct ImagePart {
  ImageDesc desc;
  const void *pixels = nullptr;
};

// An opened image file, at its first part. Single-threaded; the object owns the open file.
class ImageFile {
 public:
  virtual ~ImageFile() = default;
  virtual const ImageDesc &desc() const = 0;  // of the current part
  // Moves to part `part`; false (and no pending error) when the file has no such part.
  virtual bool seek_part(int part) = 0;
  // Rows [y_begin, y_end) of the current part (data-window coordinates), every channel as `type`,
  // interleaved. A tiled part is read in whole rows of tiles: y_begin and y_end lie on tile rows or at
  // the image's end. False on failure, with the reason in error().
  virtual bool read_rows(int y_begin, int y_end, PixelType type, void *out) = 0;
  // The last failure's text (OpenImageIO's, possibly several lines); reading it clears it.
  virtual std::string error() = 0;
};

// Texture files, tiled and MIP-mapped on demand, through one process-wide cache of bounded memory
// (OpenImageIO's TextureSystem). Every call is safe from any number of threads.
class TextureCache {
 public:
  using Handle = void *;
  // The file's handle and the description of its top level (attributes as ImageFile's), or the reason
  // (the library's text, possibly several lines).
  virtual Expected<std::pair<Handle, ImageDesc>> open(const std::string &path) const = 0;
  // Closes `path` and frees its tiles; its next open reads the file afresh.
  virtual void invalidate(const std::string &path) const = 0;
  // `channels` values at (s, t), wrapping periodically, bilinear or from the nearest texel, with zero
  // derivatives (the finest level). False on an I/O failure, whose text is dropped.
  virtual bool lookup(Handle file, bool nearest, float s, float t, int channels, float *out) const = 0;
  // Texels [x0, x1) x [y0, y1) x [z0, z1) of the top level, `channels` floats each, interleaved. False on
  // failure, with the reason in error().
  virtual bool texels(Handle file, int x0, int x1, int y0, int y1, int z0, int z1, int channels,
                      float *out) const = 0;
  virtual std::string error() const = 0;  // the calling thread's last failure; reading it clears it

 protected:
  ~TextureCache() = default;
};

class ImageIo {
 public:
  // Opens `path`; the error is the library's text (empty when it gave none).
  virtual Expected<std::unique_ptr<ImageFile>> open(const std::string &path) const = 0;
  virtual const TextureCache &textures() const = 0;

 protected:
  ~ImageIo() = default;
};

// [any-thread] The module, loaded on the first call (and kept for the process). The error names the
// module's path and why it could not be loaded.
Expected<const ImageIo *> image_io();

// [any-thread] `path` opened through the module, loaded if need be, once its header has passed
// image_header_problem (core/image_header.hpp); the error is that problem, the module's (its path and why
// it could not be loaded) or the library's text (possibly several lines, empty when it gave none).
Expected<std::unique_ptr<ImageFile>> open_image_file(const std::string &path);

// The module's one exported function: its ImageIo when `host_version` is the version it was built as.
#define NIMBUS_IMAGE_IO_ENTRY "nimbus_image_io_entry"
using ImageIoEntry = const ImageIo *(*)(const char *host_version);

}  // namespace nimbus
