// How Nimbus lays out a multi-layer EXR in memory before writing it: the description (channel names,
// compression, "nimbus:<key>" metadata) and the interleaved float pixels. Film::write_exr,
// write_layered_exr and the partial EXR's first part (partial_exr.hpp) share it, so they agree exactly.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/expected.hpp"
#include "core/image_io.hpp"
#include "film/film.hpp"

namespace nimbus {

struct ExrImage {
  ImageDesc desc;
  std::vector<float> pixels;  // desc.channels.size() per pixel, interleaved, scanlines top down
};

// Beauty is the unnamed layer (R, G, B, layer ""), so every viewer shows it by default; other elements follow
// the "<layer>.<channel>" convention OpenEXR, OIIO and Nuke split layers by: e.R, e.G, e.B, or e.Y for one
// channel.
std::vector<std::string> exr_channel_names(const std::string &layer, uint32_t channels);

// The given layers in the given order, with the metadata. Strings become "nimbus:<key>" string attributes;
// numbers become int attributes when integral and within int32, double attributes otherwise.
ExrImage layered_exr_image(uint32_t width, uint32_t height, const std::vector<ExrLayer> &layers,
                           const std::vector<std::pair<std::string, std::string>> &string_meta,
                           const std::vector<std::pair<std::string, double>> &numeric_meta);

// Every active element of `film` resolved (sums / N), named by exr_channel_names.
ExrImage film_exr_image(const Film &film, const std::vector<std::pair<std::string, std::string>> &string_meta,
                        const std::vector<std::pair<std::string, double>> &numeric_meta);

// `image` as a single-part EXR at `path`, written atomically (atomic_file.hpp).
Status write_exr_image(const std::string &path, const ExrImage &image);

}  // namespace nimbus
