// Strings a plugin supplies, as the loader shows them in a refusal: they are arbitrary bytes (a malformed
// id may hold a line break), and every refusal is one log line.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace nimbus {

// Printable ASCII as is, every other byte as \xNN, cut after 64 bytes with "...".
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
