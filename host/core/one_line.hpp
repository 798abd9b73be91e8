// Error text from a library (tinyobjloader, tinygltf, OpenImageIO) made one line, as every Error is.
#pragma once

#include <string>

namespace nimbus {

// Trailing line breaks and spaces dropped; the lines within joined with "; ".
inline std::string one_line(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
  for (size_t i = 0; (i = s.find('\n', i)) != std::string::npos;) s.replace(i, 1, "; ");
  return s;
}

}  // namespace nimbus
