// Independent models of the rough-glass furnace images (furnace_test.cpp): a small Monte Carlo path tracer
// of the same scene - the camera, the unit glass sphere, optionally the tilted glass slab, and an enclosure
// of radiance 1 - written here from the scene description alone, scattering with the reference GGX model
// of support/ggx_reference.hpp and sharing no code with the renderer.
//
// Every path that leaves the glass reaches radiance 1, and the factors 1/eta^2 that radiance picks up
// entering a closed surface cancel the eta^2 it picks up leaving it, so a pixel is E[prod of the
// per-bounce importance weights] over the bounces of its path. Drawing each bounce as a correct GGX
// sampler may (visible normal, then reflection with probability F), the correct weight is
// G2(wo, wi) / G1(wo), which the expected image uses. The lower bound uses G1(wi) instead, never larger,
// and paths the models stop after kMaxBounces (the render allows up to 127 bounces) only lose more. The
// box filter makes each pixel the mean over its square of the screen, which the models sample uniformly.
#pragma once

#include <cstdint>
#include <vector>

namespace nimbus::extremes {

// Per pixel of a width x height image, row 0 at the top: the model's mean over `paths` paths through
// uniform points of the pixel, each a lower bound of the pixel's expected value. eta: the glass's IOR;
// alpha: its GGX roughness (roughness squared); slab: whether the tilted slab of furnace_test.cpp's
// glass_furnace() stands in front of the sphere.
std::vector<double> glass_furnace_lower_bound(double eta, double alpha, bool slab, uint32_t width,
                                              uint32_t height, int paths, uint64_t seed);

// The same paths weighted by the height-correlated G2(wo, wi) / G1(wo) itself: an estimate of each pixel's
// expected value for a correct single-scattering GGX with height-correlated masking-shadowing.
std::vector<double> glass_furnace_expected(double eta, double alpha, bool slab, uint32_t width,
                                           uint32_t height, int paths, uint64_t seed);

}  // namespace nimbus::extremes
