#include "core/spectral_uplift.hpp"

#include <algorithm>
#include <cmath>

namespace nimbus {

namespace {

// Simpson's rule over [kLambdaMin, kLambdaMax] in 2.5 nm steps (an even number of intervals). The spectra
// of saturated colours have edges some 10 nm wide: at 2.5 nm the rule's RGB is within 5e-5 of a 0.1 nm
// integration for every colour of the cube (1e-5 inside it), at 5 nm only within 6e-4.
constexpr int kIntervals = 188;
constexpr int kNodes = kIntervals + 1;
static_assert(kIntervals % 2 == 0, "Simpson's rule needs an even number of intervals");

// Nodes padded with zero weights to a multiple of the lanes below, so that loops need no remainder.
constexpr int kLanes = 8;
constexpr int kPadded = (kNodes + kLanes - 1) / kLanes * kLanes;

// Per node: the normalised wavelength t, and for each channel the quadrature weight of a spectrum's value
// there times t^2, t and 1 (the derivative of the polynomial with respect to c0, c1, c2).
struct Quadrature {
  alignas(32) float t[kPadded] = {};
  alignas(32) float weight[3][3][kPadded] = {};  // [channel][coefficient][node]

  Quadrature() {
    double w[3][kNodes], sum[3] = {0, 0, 0};
    for (int k = 0; k < kNodes; ++k) {
      const float lambda = kLambdaMin + (kLambdaMax - kLambdaMin) * float(k) / kIntervals;
      t[k] = SigmoidSpectrum::normalized_wavelength(lambda);
      const double simpson = (k == 0 || k == kNodes - 1) ? 1 : (k % 2 == 1 ? 4 : 2);
      const Vec3f rgb = spectral_rgb_weight(lambda);
      for (int c = 0; c < 3; ++c) sum[c] += w[c][k] = simpson * rgb[c];
    }
    // Dividing by the rule's own integral of the constant 1 makes white exactly (1, 1, 1) here too.
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < kNodes; ++k) {
        const double v = w[c][k] / sum[c];
        weight[c][0][k] = float(v * t[k] * t[k]), weight[c][1][k] = float(v * t[k]),
        weight[c][2][k] = float(v);
      }
  }
};

const Quadrature &quadrature() {
  static const Quadrature q;
  return q;
}

// Sum of a[k] * b[k] over the padded nodes, in kLanes independent partial sums: the loop vectorises
// without reassociating floating-point sums, which the compiler may not do on its own. Its callers pass
// arrays of exactly kPadded floats; unchecked by the sanitizers, whose per-load checks made the table's
// fit (nearly all in this loop) eight times slower and every spectral test under them 13 s long.
__attribute__((no_sanitize("address", "undefined"))) float node_sum(const float *a, const float *b) {
  float lane[kLanes] = {};
  for (int k = 0; k < kPadded; k += kLanes)
    for (int l = 0; l < kLanes; ++l) lane[l] += a[k + l] * b[k + l];
  float sum = 0;
  for (float v : lane) sum += v;
  return sum;
}

// A spectrum's RGB minus the target, and its derivatives with respect to (c0, c1, c2). The sums are in
// float (vectorised); the solver takes them in double, as its normal equations square J's condition.
struct Evaluation {
  double rgb[3] = {0, 0, 0};
  double jacobian[3][3] = {};  // [channel][coefficient]
};

Evaluation evaluate(const double c[3], const Vec3f &target) {
  const Quadrature &q = quadrature();
  alignas(32) float s[kPadded], ds[kPadded];  // the sigmoid and its derivative d/dx at each node
  const float c0 = float(c[0]), c1 = float(c[1]), c2 = float(c[2]);
  for (int k = 0; k < kPadded; ++k) {
    const float t = q.t[k], x = (c0 * t + c1) * t + c2;
    const float inv = 1 / std::sqrt(1 + x * x);
    s[k] = 0.5f + 0.5f * x * inv, ds[k] = 0.5f * inv * inv * inv;
  }
  Evaluation e;
  for (int ch = 0; ch < 3; ++ch) {
    e.rgb[ch] = double(node_sum(q.weight[ch][2], s)) - target[ch];
    for (int j = 0; j < 3; ++j) e.jacobian[ch][j] = node_sum(q.weight[ch][j], ds);
  }
  return e;
}

double squared_norm(const double r[3]) { return r[0] * r[0] + r[1] * r[1] + r[2] * r[2]; }
double max_abs(const double r[3]) { return std::max({std::abs(r[0]), std::abs(r[1]), std::abs(r[2])}); }

double determinant(const double m[3][3]) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

// Solves a x = b by Cramer's rule; false when a is singular.
bool solve3(const double a[3][3], const double b[3], double x[3]) {
  const double det = determinant(a);
  if (!(std::abs(det) > 1e-300)) return false;
  for (int col = 0; col < 3; ++col) {
    double m[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m[i][j] = j == col ? b[i] : a[i][j];
    x[col] = determinant(m) / det;
  }
  return std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2]);
}

// Colours the model cannot reach (dark saturated ones and, as 1 - s(x) = s(-x), their complements near
// white) drive the coefficients towards infinity, into edges far narrower than the quadrature resolves.
// The fit stops at this bound, which every reachable colour stays within (the primaries need about 240)...
constexpr double kCoefficientLimit = 1000;
// ...or once this many iterations in a row have not taken a tenth off the squared error.
constexpr int kStallLimit = 4;
constexpr double kTolerance = 1e-6;  // per RGB channel: a few times the rounding of the float sums

}  // namespace

SigmoidSpectrum constant_sigmoid_spectrum(float g) {
  const float x = SigmoidSpectrum::sigmoid_inverse(clamp(g, 0.0f, 1.0f));
  return {0, 0, clamp(x, -kSigmoidSaturated, kSigmoidSaturated)};
}

Vec3f reflectance_rgb(const SigmoidSpectrum &s) {
  const double c[3] = {s.c0, s.c1, s.c2};
  const Evaluation e = evaluate(c, Vec3f(0));
  return {float(e.rgb[0]), float(e.rgb[1]), float(e.rgb[2])};
}

ReflectanceFit refine_reflectance_fit(const Vec3f &rgb, const SigmoidSpectrum &start, int max_iterations) {
  double c[3] = {start.c0, start.c1, start.c2};
  Evaluation e = evaluate(c, rgb);
  double err = squared_norm(e.rgb);
  double damping = 1e-4;  // relative to the diagonal (Marquardt's scaling); small: mostly Newton steps
  int stalled = 0;        // iterations in a row that took less than a tenth off the squared error
  for (int it = 0; it < max_iterations && max_abs(e.rgb) > kTolerance && stalled < kStallLimit; ++it) {
    // Normal equations (J^T J + damping diag(J^T J)) step = -J^T r.
    double a[3][3], g[3], step[3];
    for (int i = 0; i < 3; ++i) {
      g[i] = 0;
      for (int ch = 0; ch < 3; ++ch) g[i] -= e.jacobian[ch][i] * e.rgb[ch];
      for (int j = 0; j < 3; ++j) {
        a[i][j] = 0;
        for (int ch = 0; ch < 3; ++ch) a[i][j] += e.jacobian[ch][i] * e.jacobian[ch][j];
      }
    }
    for (int i = 0; i < 3; ++i) a[i][i] *= 1 + damping;
    const double previous = err;
    if (solve3(a, g, step)) {
      const double next[3] = {c[0] + step[0], c[1] + step[1], c[2] + step[2]};
      const bool bounded =
          std::max({std::abs(next[0]), std::abs(next[1]), std::abs(next[2])}) <= kCoefficientLimit;
      const Evaluation en = bounded ? evaluate(next, rgb) : e;
      if (bounded && squared_norm(en.rgb) < err) {
        std::copy(next, next + 3, c), e = en, err = squared_norm(en.rgb);
        damping = std::max(damping * 0.1, 1e-9);
      } else {
        damping *= 10;
      }
    } else {
      damping *= 10;
    }
    stalled = err < 0.9 * previous ? 0 : stalled + 1;
  }
  return {{float(c[0]), float(c[1]), float(c[2])}, float(max_abs(e.rgb))};
}

ReflectanceFit fit_reflectance_with_error(Vec3f rgb) {
  for (int i = 0; i < 3; ++i) rgb[i] = std::isnan(rgb[i]) ? 0.0f : clamp(rgb[i], 0.0f, 1.0f);
  if (rgb.x == rgb.y && rgb.y == rgb.z) return {constant_sigmoid_spectrum(rgb.x), 0};
  // Continuation: from the grey of the same mean, whose spectrum is exact, through colours ever closer to
  // rgb, each fit starting from the last. A cold start at a saturated colour can stall in the sigmoid's
  // flat tails; small steps keep every start within Newton's reach.
  const float mean = (rgb.x + rgb.y + rgb.z) / 3;
  const Vec3f grey(mean);
  // The grey's exact spectrum, kept off the saturated constants so that it has a usable slope.
  ReflectanceFit fit{constant_sigmoid_spectrum(clamp(mean, 1e-3f, 1 - 1e-3f)), 0};
  constexpr int kSteps = 8;
  for (int i = 1; i <= kSteps; ++i) {
    const Vec3f target = grey + (rgb - grey) * (float(i) / kSteps);
    fit = refine_reflectance_fit(target, fit.spectrum, i == kSteps ? 60 : 15);
  }
  return fit;
}

UpliftedEmission fit_emission(Vec3f rgb) {
  rgb = max(rgb, Vec3f(0));
  const float scale = 2 * max_component(rgb);
  if (!(scale > 0) || !std::isfinite(scale)) return {constant_sigmoid_spectrum(0), 0};
  return {fit_reflectance(rgb / scale), scale};
}

}  // namespace nimbus
