#include "core/image_header.hpp"

#include <array>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/checksum.hpp"
#include "core/one_line.hpp"

namespace nimbus {
namespace {

std::string too_long(const std::string &what, uint64_t size, uint64_t offset, uint64_t file_size) {
  return what + " claims " + std::to_string(size) + " bytes at byte " + std::to_string(offset) +
         " of a file of " + std::to_string(file_size);
}

// Attributes are `name\0type\0size value`; an empty name ends a header, and an empty header ends the
// headers of a multi-part file.
std::optional<std::string> exr_problem(std::ifstream &in, bool multipart, uint64_t file_size) {
  for (bool header_empty = true;;) {
    std::string name, type;
    if (!std::getline(in, name, '\0')) return std::nullopt;
    if (name.empty()) {
      if (!multipart || header_empty) return std::nullopt;
      header_empty = true;
      continue;
    }
    std::array<uint8_t, 4> size_bytes{};
    if (!std::getline(in, type, '\0') || !in.read(reinterpret_cast<char *>(size_bytes.data()), 4))
      return std::nullopt;
    const auto size = int32_t(load_le(size_bytes.data(), 4));
    const auto offset = uint64_t(in.tellg());
    if (size < 0 || uint64_t(size) > file_size - offset)
      return too_long("attribute '" + shown(name) + "'", uint64_t(uint32_t(size)), offset, file_size);
    in.seekg(size, std::ios::cur);
    header_empty = false;
  }
}

// Chunks are `length type data crc`, the length big-endian; IEND is the last.
std::optional<std::string> png_problem(std::ifstream &in, uint64_t file_size) {
  for (uint64_t offset = 8; offset + 8 <= file_size;) {
    std::array<uint8_t, 8> head{};
    if (!in.seekg(std::streamoff(offset)) || !in.read(reinterpret_cast<char *>(head.data()), 8))
      return std::nullopt;
    const uint64_t length =
        uint64_t(head[0]) << 24 | uint64_t(head[1]) << 16 | uint64_t(head[2]) << 8 | head[3];
    const std::string type(reinterpret_cast<const char *>(head.data() + 4), 4);
    if (length + 12 > file_size - offset)
      return too_long("chunk '" + shown(type) + "'", length, offset, file_size);
    if (type == "IEND") return std::nullopt;
    offset += 12 + length;
  }
  return std::nullopt;
}

// The file's extension in lower case, with its dot.
std::string lower_extension(const std::string &path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char &c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace

std::optional<std::string> image_header_problem(const std::string &path) {
  std::error_code ec;
  const uint64_t file_size = std::filesystem::file_size(path, ec);
  if (ec) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  std::array<uint8_t, 8> start{};
  in.read(reinterpret_cast<char *>(start.data()), start.size());
  const auto got = size_t(in.gcount());
  const bool exr = got >= 4 && load_le(start.data(), 4) == 20000630;  // OpenEXR's magic number
  const bool png = got == 8 && std::memcmp(start.data(), "\x89PNG\r\n\x1a\n", 8) == 0;
  // OpenImageIO tries every reader on a file its extension's reader refuses, and some accept a few bytes
  // of anything as a huge image (WebP's takes a lone 0x2f byte for a lossless bitstream and decodes the
  // size it claims, ~600 MB for 55 bytes): a file named as OpenEXR or PNG must be one.
  const std::string ext = lower_extension(path);
  if (ext == ".exr" && !exr) return "not an OpenEXR file: it does not start with OpenEXR's magic number";
  if (ext == ".png" && !png) return "not a PNG file: it does not start with the PNG signature";
  if (exr) return exr_problem(in, start[5] & 0x10, file_size);  // version field bit 12: multi-part
  if (png) return png_problem(in, file_size);
  return std::nullopt;
}

}  // namespace nimbus
