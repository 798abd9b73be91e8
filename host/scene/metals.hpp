// Complex indices of refraction of common metals as RGB triples: the measured n and k spectra pbrt-v4 ships
// (metal-Au-eta, metal-Au-k, ...) each projected onto linear Rec.709, through the CIE 1931 colour matching
// functions over 360-830 nm and the XYZ-to-Rec.709 matrix, as Mitsuba 3's RGB mode reduces spectral data
// (no illuminant, unclamped). A projection, not a sample at one wavelength per channel;
// tests/scene/metals_test.cpp checks the values against the spectra.
#pragma once

#include <array>
#include <optional>
#include <string_view>

#include <nimbus/cpp/math.hpp>

namespace nimbus {

struct MetalIor {
  std::string_view name;
  Rgb eta, k;
};

inline constexpr std::array<MetalIor, 5> kMetals{{
    {"gold", {0.143f, 0.374f, 1.442f}, {3.983f, 2.385f, 1.603f}},
    {"silver", {0.155f, 0.117f, 0.138f}, {4.828f, 3.122f, 2.147f}},
    {"copper", {0.200f, 0.924f, 1.102f}, {3.912f, 2.452f, 2.142f}},
    {"aluminium", {1.657f, 0.880f, 0.521f}, {9.224f, 6.270f, 4.837f}},
    {"aluminum", {1.657f, 0.880f, 0.521f}, {9.224f, 6.270f, 4.837f}},
}};

inline std::optional<MetalIor> find_metal(std::string_view name) {
  for (const MetalIor &m : kMetals)
    if (m.name == name) return m;
  return std::nullopt;
}

}  // namespace nimbus
