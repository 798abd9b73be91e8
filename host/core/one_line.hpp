// Text for errors, which are one line each: a library's error text (tinyobjloader, tinygltf, OpenImageIO)
// joined into one line, and strings read from a file or a plugin shown safely inside a message.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace nimbus {

// Trailing line breaks and spaces dropped; the lines within joined with "; ".
inline std::string one_line(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
  for (size_t i = 0; (i = s.find('\n', i)) != std::string::npos;) s.replace(i, 1, "; ");
  return s;
}

// A string the host did not write (a plugin's id, an element name in a checkpoint), as a message shows
// it: arbitrary bytes may hold a line break. Printable ASCII as is, every other byte as \xNN, cut after
// 64 bytes with "...".
inline std::string shown(std::string_view text) {
  constexpr size_t kMax = 64;
  std::string out;
  for (size_t i = 0; i < text.size() && i < kMax; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += char(c);
    } else {
      char hex[5];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    }
  }
  return text.size() > kMax ? out + "..." : out;
}

}  // namespace nimbus
