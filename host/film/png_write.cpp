#include "film/png_write.hpp"

#include <png.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <vector>

namespace nimbus {
namespace {

// libpng reports an error by calling this, which must not return: the message is kept and control goes
// back to write_png_file's setjmp.
[[noreturn]] void on_error(png_structp png, png_const_charp message) {
  auto *reason = static_cast<std::string *>(png_get_error_ptr(png));
  *reason = message;
  std::longjmp(png_jmpbuf(png), 1);
}

void on_warning(png_structp, png_const_charp) {}

}  // namespace

Status write_png_file(const std::string &file, const ImagePart &image) {
  const ImageDesc &desc = image.desc;
  static const int kColourTypes[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                     PNG_COLOR_TYPE_RGB_ALPHA};
  const size_t channels = desc.channels.size();
  if (desc.type != PixelType::UInt8 || channels < 1 || channels > 4)
    return Error{"PNG holds 1 to 4 channels of 8 bits"};
  // Everything with a destructor is made before setjmp, so that a longjmp from libpng skips none.
  std::vector<png_bytep> rows(size_t(desc.height));
  for (size_t y = 0; y < rows.size(); ++y)
    rows[y] = const_cast<png_bytep>(static_cast<const png_byte *>(image.pixels)) +
              y * size_t(desc.width) * channels;
  std::vector<png_text> texts;
  for (const ImageAttribute &a : desc.attributes)
    if (a.kind == ImageAttribute::Kind::String)
      texts.push_back({PNG_TEXT_COMPRESSION_NONE, const_cast<char *>(a.name.c_str()),
                       const_cast<char *>(a.text.c_str()), a.text.size(), 0, nullptr, nullptr});
  std::string reason;
  std::FILE *f = std::fopen(file.c_str(), "wb");
  if (!f) return Error{std::strerror(errno)};
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &reason, on_error, on_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    std::fclose(f);
    return Error{"out of memory"};
  }
  errno = 0;  // so that a failed write's errno is its own
  if (setjmp(png_jmpbuf(png))) {
    // libpng says only "Write Error" when fwrite fails (a full disk): the system says why.
    if (errno != 0) reason += std::string(": ") + std::strerror(errno);
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
    return Error{reason};
  }
  png_init_io(png, f);
  png_set_IHDR(png, info, png_uint_32(desc.width), png_uint_32(desc.height), 8, kColourTypes[channels - 1],
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (!texts.empty()) png_set_text(png, info, texts.data(), int(texts.size()));
  png_write_info(png, info);
  png_write_image(png, rows.data());
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  // A full disk may only show when the buffered data reaches it.
  const bool failed = std::ferror(f) != 0;
  const int saved = errno;
  if (std::fclose(f) != 0 || failed) return Error{std::strerror(failed ? saved : errno)};
  return Ok{};
}

}  // namespace nimbus
