#include "film/exr_header.hpp"

#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>

#include "core/checksum.hpp"
#include "core/one_line.hpp"

namespace nimbus {

std::optional<std::string> exr_header_problem(const std::string &path) {
  std::error_code ec;
  const uintmax_t file_size = std::filesystem::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  std::array<uint8_t, 8> start{};
  if (ec || !in.read(reinterpret_cast<char *>(start.data()), start.size())) return std::nullopt;
  if (load_le(start.data(), 4) != 20000630) return std::nullopt;  // OpenEXR's magic number
  const bool multipart = start[5] & 0x10;                         // version field, bit 12

  // Attributes are `name\0type\0size value`; an empty name ends a header, and an empty header ends the
  // headers of a multi-part file.
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
    const auto offset = uintmax_t(in.tellg());
    if (size < 0 || uintmax_t(size) > file_size - offset)
      return "attribute '" + shown(name) + "' claims " + std::to_string(size) + " bytes at byte " +
             std::to_string(offset) + " of a file of " + std::to_string(file_size);
    in.seekg(size, std::ios::cur);
    header_empty = false;
  }
}

}  // namespace nimbus
