// Reading a Nimbus multi-layer EXR back: for tests, checkpoints and `nimbus compare`.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/expected.hpp"

namespace nimbus {

struct ImageLayer {
  std::vector<std::string> channel_names;  // full names, e.g. {"albedo.R", "albedo.G", "albedo.B"}
  std::vector<float> data;                 // width * height * channel_names.size(), interleaved
};

struct ImageLayers {
  uint32_t width = 0, height = 0;
  // Full channel name ("R", "albedo.G", "depth.Y") -> one plane of width * height floats.
  std::map<std::string, std::vector<float>> channels;
  // Layer name -> its channels interleaved; the unprefixed R, G, B form the layer "beauty". Layers are
  // split at the last '.', so "lightmix.key.R" belongs to "lightmix.key".
  std::map<std::string, ImageLayer> layers;
  // Header attributes under their full names ("nimbus:iterations", "Software", "compression"):
  // strings, and scalar numbers of any width (integers read back exactly).
  std::map<std::string, std::string> strings;
  std::map<std::string, double> numbers;
};

Expected<ImageLayers> read_exr_layers(const std::string &path);
// The size and header attributes alone (no channels), without reading pixels.
Expected<ImageLayers> read_exr_header(const std::string &path);

}  // namespace nimbus
