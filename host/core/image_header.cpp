#include "core/image_header.hpp"

#include <array>
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

}  // namespace

std::optional<std::string> image_header_problem(const std::string &path) {
  std::error_code ec;
  const uint64_t file_size = std::filesystem::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  std::array<uint8_t, 8> start{};
  if (ec || !in.read(reinterpret_cast<char *>(start.data()), start.size())) return std::nullopt;
  if (load_le(start.data(), 4) == 20000630)  // OpenEXR's magic number; version field bit 12: multi-part
    return exr_problem(in, start[5] & 0x10, file_size);
  if (std::memcmp(start.data(), "\x89PNG\r\n\x1a\n", 8) == 0) return png_problem(in, file_size);
  return std::nullopt;
}

}  // namespace nimbus
