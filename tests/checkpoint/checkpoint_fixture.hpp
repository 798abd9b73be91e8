// Films with known contents for the checkpoint format tests.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "film/checkpoint.hpp"
#include "film/film.hpp"

namespace nimbus::test {

inline constexpr uint32_t kWidth = 7, kHeight = 5;  // odd, so row/column mix-ups show

// A film of `width` x `height` with albedo (RGB), depth (Y), lightmix.key (RGB, splatted) and normal
// registered, `requested` of them requested and allocated, three splat workers.
std::unique_ptr<Film> make_film(const std::vector<std::string> &requested = {"albedo", "depth",
                                                                             "lightmix.key"},
                                uint32_t width = kWidth, uint32_t height = kHeight);

// One iteration of samples that depend only on `iteration`: values over many binades (so any rounding or
// reordering shows in the last bits), splats on several workers, merged, and in iteration 1 one NaN
// sample. Ends the iteration.
void add_iteration(Film &film, uint64_t iteration);

// What the render session would pass for this film.
CheckpointInfo make_info();

// Bit patterns of an element's sums, for exact comparison.
std::vector<uint64_t> sum_bits(const Film &film, const std::string &element);

}  // namespace nimbus::test
