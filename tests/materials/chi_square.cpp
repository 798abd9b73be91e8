#include "chi_square.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

namespace nimbus::test {

namespace {

constexpr double kPiD = std::numbers::pi;

double square(double x) { return x * x; }

// pdf times the sin(theta) Jacobian of the theta/phi parametrisation, in one histogram bin. Points on the
// bin's theta edges move inside by a negligible amount so that each bin sees its own side of the horizon
// (every BSDF is discontinuous there and the horizon is a bin edge); otherwise the quadrature would refine
// along that edge down to its depth limit.
struct Integrand {
  const DirectionPdf &pdf;
  double theta_lo, theta_hi;
  double operator()(double theta, double phi) const {
    return integrand_at(std::clamp(theta, theta_lo, theta_hi), phi);
  }
  double integrand_at(double theta, double phi) const;
};

double Integrand::integrand_at(double theta, double phi) const {
  const double st = std::sin(theta);
  if (st <= 0) return 0;
  const Vec3f w(static_cast<float>(st * std::cos(phi)), static_cast<float>(st * std::sin(phi)),
                static_cast<float>(std::cos(theta)));
  return pdf(w) * st;
}

// Tensor-product Simpson rule on a rectangle from its 3x3 samples.
double simpson(const double v[3][3], double hx, double hy) {
  constexpr double w[3] = {1, 4, 1};
  double sum = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) sum += w[i] * w[j] * v[i][j];
  return sum * hx * hy / 36;
}

// Relative tolerance: far below the statistical noise of a cell expecting 1e6 samples (1e-3).
constexpr double kRelTol = 1e-4;
constexpr int kMaxDepth = 6;

// Adaptive Simpson on rectangles: compare the rule on the cell with the rule on its four quarters, refine
// where they disagree. Unlike nested 1D quadrature the error estimate is never polluted by the noise of an
// inner integration, so narrow GGX peaks are resolved without runaway refinement.
double refine(const Integrand &f, double x0, double x1, double y0, double y1, const double v[3][3],
              double whole, double abs_tol, int depth) {
  double g[5][5];
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      g[i][j] =
          (i % 2 == 0 && j % 2 == 0) ? v[i / 2][j / 2] : f(x0 + (x1 - x0) * i / 4, y0 + (y1 - y0) * j / 4);
  const double hx = (x1 - x0) / 2, hy = (y1 - y0) / 2;
  double child[2][2][3][3];
  double est[2][2], sum = 0;
  for (int cx = 0; cx < 2; ++cx)
    for (int cy = 0; cy < 2; ++cy) {
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) child[cx][cy][i][j] = g[2 * cx + i][2 * cy + j];
      est[cx][cy] = simpson(child[cx][cy], hx, hy);
      sum += est[cx][cy];
    }
  if (depth == 0 || std::abs(sum - whole) <= 15 * std::max(abs_tol, kRelTol * std::abs(sum)))
    return sum + (sum - whole) / 15;
  double total = 0;
  for (int cx = 0; cx < 2; ++cx)
    for (int cy = 0; cy < 2; ++cy)
      total += refine(f, x0 + cx * hx, x0 + (cx + 1) * hx, y0 + cy * hy, y0 + (cy + 1) * hy, child[cx][cy],
                      est[cx][cy], abs_tol / 4, depth - 1);
  return total;
}

// Regularised upper incomplete gamma Q(a, x) (series below a + 1, Lentz's continued fraction above).
double gamma_q(double a, double x) {
  if (x <= 0) return 1;
  const double log_prefix = -x + a * std::log(x) - std::lgamma(a);
  constexpr double kEps = 1e-15, kTiny = 1e-300;
  if (x < a + 1) {
    double ap = a, del = 1 / a, sum = del;
    for (int n = 0; n < 100000 && std::abs(del) > std::abs(sum) * kEps; ++n) {
      ap += 1;
      del *= x / ap;
      sum += del;
    }
    return std::max(0.0, 1 - sum * std::exp(log_prefix));
  }
  double b = x + 1 - a, c = 1 / kTiny, d = 1 / b, h = d;
  for (int i = 1; i < 100000; ++i) {
    const double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1) < kEps) break;
  }
  return std::exp(log_prefix) * h;
}

}  // namespace

double chi_square_survival(double statistic, int dof) { return gamma_q(dof / 2.0, statistic / 2.0); }

double sidak_significance(double alpha, int tests) { return 1 - std::pow(1 - alpha, 1.0 / tests); }

double integrate_pdf_cell(const DirectionPdf &pdf, double theta0, double theta1, double phi0, double phi1) {
  // Start from a 4x4 split so that a lobe narrower than the cell cannot hide between the first samples.
  constexpr int kSplit = 2;
  const double dt = (theta1 - theta0) / kSplit, dp = (phi1 - phi0) / kSplit;
  // Absolute tolerance per cell, in probability: 1e-4 samples out of 1e6.
  const double abs_tol = 1e-8 / (kSplit * kSplit);
  const double nudge = 1e-7 * (theta1 - theta0);
  const Integrand f{pdf, theta0 + nudge, theta1 - nudge};
  double total = 0;
  for (int a = 0; a < kSplit; ++a)
    for (int b = 0; b < kSplit; ++b) {
      const double x0 = theta0 + a * dt, y0 = phi0 + b * dp;
      double v[3][3];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) v[i][j] = f(x0 + dt * i / 2, y0 + dp * j / 2);
      total += refine(f, x0, x0 + dt, y0, y0 + dp, v, simpson(v, dt, dp), abs_tol, kMaxDepth);
    }
  // Richardson extrapolation can undershoot next to a peak; a probability is never negative.
  return std::max(0.0, total);
}

std::string ChiSquareResult::describe() const {
  char buf[256];
  std::snprintf(
      buf, sizeof buf,
      "p = %.3g, chi2 = %.1f, dof = %d, worst cell %.2f sigma, pdf integral = %.5f, failed = %.5f%s%s",
      p_value, statistic, dof, worst_sigma, pdf_integral, failed_fraction, error.empty() ? "" : ", ",
      error.c_str());
  return buf;
}

ChiSquareResult chi_square_test(const DirectionSampler &sample, const DirectionPdf &pdf,
                                const ChiSquareConfig &config) {
  const int nt = config.theta_bins, np = config.phi_bins, cells = nt * np;
  std::vector<double> observed(cells + 1, 0), expected(cells + 1, 0);  // last: failed samples

  Pcg32 rng(config.seed);
  for (int s = 0; s < config.samples; ++s) {
    const std::optional<Vec3f> w = sample(rng);
    if (!w) {
      observed[cells] += 1;
      continue;
    }
    const double theta = std::acos(std::clamp(static_cast<double>(w->z), -1.0, 1.0));
    double phi = std::atan2(static_cast<double>(w->y), static_cast<double>(w->x));
    if (phi < 0) phi += 2 * kPiD;
    const int it = std::min(static_cast<int>(theta / kPiD * nt), nt - 1);
    const int ip = std::min(static_cast<int>(phi / (2 * kPiD) * np), np - 1);
    observed[it * np + ip] += 1;
  }

  ChiSquareResult result;
  double integral = 0;
  for (int it = 0; it < nt; ++it)
    for (int ip = 0; ip < np; ++ip) {
      const double p = integrate_pdf_cell(pdf, kPiD * it / nt, kPiD * (it + 1) / nt, 2 * kPiD * ip / np,
                                          2 * kPiD * (ip + 1) / np);
      expected[it * np + ip] = p * config.samples;
      integral += p;
    }
  result.pdf_integral = integral;
  result.failed_fraction = observed[cells] / config.samples;
  expected[cells] = std::max(0.0, 1 - integral) * config.samples;

  const ChiSquareResult counted = chi_square_counts(observed, expected, config.min_expected);
  result.statistic = counted.statistic;
  result.dof = counted.dof;
  result.worst_sigma = counted.worst_sigma;
  result.p_value = counted.p_value;
  result.error = counted.error;
  return result;
}

ChiSquareResult chi_square_counts(const std::vector<double> &observed, const std::vector<double> &expected,
                                  double min_expected) {
  ChiSquareResult result;
  const int cells = static_cast<int>(expected.size()) - 1;
  // Pool every category expecting fewer than min_expected samples (and, if the pool is still too small,
  // the next smallest ones) into one; everything else contributes its own term.
  std::vector<int> order(cells + 1);
  for (int i = 0; i <= cells; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return expected[a] < expected[b]; });
  double pool_obs = 0, pool_exp = 0, chi2 = 0;
  int dof = 0;
  for (int i : order) {
    if (expected[i] < min_expected || (pool_obs + pool_exp > 0 && pool_exp < min_expected)) {
      pool_obs += observed[i];
      pool_exp += expected[i];
    } else {
      chi2 += square(observed[i] - expected[i]) / expected[i];
      result.worst_sigma =
          std::max(result.worst_sigma, std::abs(observed[i] - expected[i]) / std::sqrt(expected[i]));
      ++dof;
    }
  }
  if (pool_obs > 0 && pool_exp <= 0) {
    result.error = "samples fell where the pdf integrates to zero";
    return result;
  }
  if (pool_exp > 0) {
    chi2 += square(pool_obs - pool_exp) / pool_exp;
    result.worst_sigma = std::max(result.worst_sigma, std::abs(pool_obs - pool_exp) / std::sqrt(pool_exp));
    ++dof;
  }
  dof -= 1;  // the total is fixed; no parameters were fitted
  result.statistic = chi2;
  result.dof = dof;
  if (dof <= 0) {
    result.error = "too few populated cells for a chi-square test";
    return result;
  }
  result.p_value = chi_square_survival(chi2, dof);
  return result;
}

}  // namespace nimbus::test
