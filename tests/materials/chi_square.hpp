// Chi-square goodness-of-fit of a direction sampler against its claimed pdf, in the style of pbrt-v3's
// chi2 test: histogram the samples over a theta/phi grid of the sphere, integrate the pdf over each cell
// for the expected counts, pool sparse cells, and turn the statistic into a p-value.
//
// Failed samples form one more category whose expected share is 1 - integral of the pdf, so a sampler that
// fails more or less often than its pdf admits is caught too.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nimbus/cpp/math.hpp>
#include "test_helpers.hpp"

namespace nimbus::test {

struct ChiSquareConfig {
  int theta_bins = 40;
  int phi_bins = 80;
  int samples = 1'000'000;
  uint64_t seed = 1;
  double min_expected = 5;  // cells expecting fewer samples are pooled (the chi-square approximation)
};

struct ChiSquareResult {
  double p_value = 0;
  double statistic = 0;
  int dof = 0;
  // The largest |observed - expected| / sqrt(expected) of a category (the pool of sparse ones counts as
  // one): how many standard deviations the worst cell is off.
  double worst_sigma = 0;
  double pdf_integral = 0;  // of the pdf over the sphere
  double failed_fraction = 0;
  std::string error;  // non-empty: rejected outright (e.g. samples where the pdf integrates to zero)
  std::string describe() const;
};

// Draws one direction, or nothing when the sampler fails.
using DirectionSampler = std::function<std::optional<Vec3f>(Pcg32 &)>;
using DirectionPdf = std::function<double(const Vec3f &)>;

ChiSquareResult chi_square_test(const DirectionSampler &sample, const DirectionPdf &pdf,
                                const ChiSquareConfig &config);

// The chi-square statistic of observed against expected counts per category (same length), pooling the
// categories that expect fewer than `min_expected` as chi_square_test does; fills statistic, dof, p_value
// or error.
ChiSquareResult chi_square_counts(const std::vector<double> &observed, const std::vector<double> &expected,
                                  double min_expected);

// Per-test significance so that `tests` independent tests together reject a correct sampler with
// probability `alpha` (Sidak correction).
double sidak_significance(double alpha, int tests);

// Upper tail of the chi-square distribution with `dof` degrees of freedom.
double chi_square_survival(double statistic, int dof);

// The pdf integrated over [theta0, theta1] x [phi0, phi1] by adaptive 2D Simpson quadrature.
double integrate_pdf_cell(const DirectionPdf &pdf, double theta0, double theta1, double phi0, double phi1);

}  // namespace nimbus::test
