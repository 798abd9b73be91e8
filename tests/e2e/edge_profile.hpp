// Vertical edges of emitters on black, rendered through the CLI and measured across: the mean profile
// over many rows (each row is an independent estimate of the same columns, so their spread gives every
// standard error) and its predicted value from the blur kernels that act on the edge. Used by the
// depth-of-field and pixel-filter tests.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "e2e_support.hpp"

namespace nimbus::e2e {

// A render of one channel (all emitters are grey, so R stands for all).
struct Frame {
  uint32_t width = 0, height = 0;
  std::vector<float> r;
  double at(uint32_t x, uint32_t y) const { return r[size_t(y) * width + x]; }
};

// Writes `yaml` into `dir`, renders it with `args` added, and reads R back (empty on failure, recorded).
inline Frame render_frame(const TestDir &dir, const std::string &name, const std::string &yaml,
                          const std::vector<std::string> &args = {}) {
  const std::string path = dir.file(name + ".yaml"), exr = dir.file(name + ".exr");
  write_bytes(path, yaml);
  std::vector<std::string> argv = {"render", path, "-o", exr, "-q"};
  argv.insert(argv.end(), args.begin(), args.end());
  const ProcessResult r = run_nimbus(argv, dir);
  if (!exited_with(r, 0)) {
    ADD_FAILURE() << r.describe();
    return {};
  }
  const auto img = read_exr(exr);
  if (!img) return {};
  return {img->width, img->height, plane(*img, "R")};
}

// A 1-D density of a film offset in pixels, tabulated on [-reach, reach] in steps of kStep.
struct Kernel {
  static constexpr double kStep = 1.0 / 512;
  double reach = 0;
  std::vector<double> p;  // normalised to sum 1
  // f: the (unnormalised) density at t, 0 outside [-reach, reach].
  static Kernel of(double reach, const std::function<double(double)> &f) {
    Kernel k{reach, {}};
    double sum = 0;
    for (double t = -reach + kStep / 2; t < reach; t += kStep) k.p.push_back(f(t)), sum += k.p.back();
    for (double &v : k.p) v /= sum;
    return k;
  }
  // The density of the sum of two independent offsets.
  Kernel plus(const Kernel &o) const {
    Kernel k{reach + o.reach, std::vector<double>(p.size() + o.p.size() - 1, 0)};
    for (size_t i = 0; i < p.size(); ++i)
      for (size_t j = 0; j < o.p.size(); ++j) k.p[i + j] += p[i] * o.p[j];
    return k;
  }
  // P(offset < t).
  double cdf(double t) const {
    double s = 0;
    for (size_t i = 0; i < p.size() && -reach + (double(i) + 0.5) * kStep < t; ++i) s += p[i];
    return s;
  }
};

// The x-marginal of a uniform disk of radius R: the circle of confusion of a thin lens.
inline Kernel disk_marginal(double R) {
  return Kernel::of(R, [R](double t) { return std::sqrt(std::max(0.0, R * R - t * t)); });
}

// Columns [x0, x1) across an edge at film x = `edge` (emitter on its left) over rows [y0, y1): the mean
// value of each column, its standard error, and the edge's width: W^2 = sum_k t_k^2 (v_k - v_{k+1}), the
// second moment of the line spread function about the edge (t_k = edge - (k + 1) is where columns k and
// k + 1 meet, measured from the edge). W^2 is linear in the pixels, so its mean over rows is unbiased.
struct EdgeProfile {
  uint32_t x0 = 0;
  std::vector<double> mean, se;
  double width2 = 0, width2_se = 0;
};

inline double width2_of(const std::function<double(uint32_t)> &v, uint32_t x0, uint32_t x1, double edge) {
  double w2 = 0;
  for (uint32_t k = x0; k + 1 < x1; ++k) w2 += (edge - (k + 1)) * (edge - (k + 1)) * (v(k) - v(k + 1));
  return w2;
}

inline EdgeProfile measure_edge(const Frame &f, double edge, uint32_t x0, uint32_t x1, uint32_t y0,
                                uint32_t y1) {
  EdgeProfile e;
  e.x0 = x0;
  const double rows = y1 - y0;
  std::vector<double> w2(y1 - y0);
  for (uint32_t y = y0; y < y1; ++y)
    w2[y - y0] = width2_of([&](uint32_t x) { return f.at(x, y); }, x0, x1, edge);
  for (uint32_t x = x0; x < x1; ++x) {
    double m = 0, s2 = 0;
    for (uint32_t y = y0; y < y1; ++y) m += f.at(x, y) / rows;
    for (uint32_t y = y0; y < y1; ++y) s2 += (f.at(x, y) - m) * (f.at(x, y) - m) / (rows - 1);
    e.mean.push_back(m), e.se.push_back(std::sqrt(s2 / rows));
  }
  for (double v : w2) e.width2 += v / rows;
  for (double v : w2) e.width2_se += (v - e.width2) * (v - e.width2) / (rows - 1);
  e.width2_se = std::sqrt(e.width2_se / rows);
  return e;
}

// The expected profile of that edge when the film offsets follow `k`: column x sees the emitter when
// x + 0.5 + offset < edge.
inline std::vector<double> predicted_edge(const Kernel &k, double edge, uint32_t x0, uint32_t x1) {
  std::vector<double> v;
  for (uint32_t x = x0; x < x1; ++x) v.push_back(k.cdf(edge - (x + 0.5)));
  return v;
}

// Checks a measured edge against its prediction: every column within `sigmas` standard errors (plus
// `slack` where every row agrees, e.g. columns wholly on one side), and W^2 within `sigmas` standard
// errors. Returns the measured width W in pixels.
inline double expect_edge(const EdgeProfile &m, const Kernel &k, double edge, double sigmas, double slack) {
  const uint32_t x1 = m.x0 + uint32_t(m.mean.size());
  const std::vector<double> want = predicted_edge(k, edge, m.x0, x1);
  for (size_t i = 0; i < want.size(); ++i)
    EXPECT_NEAR(m.mean[i], want[i], sigmas * m.se[i] + slack) << "column " << m.x0 + i;
  const double want2 = width2_of([&](uint32_t x) { return want[x - m.x0]; }, m.x0, x1, edge);
  EXPECT_NEAR(m.width2, want2, sigmas * m.width2_se + 1e-3)
      << "edge width " << std::sqrt(std::max(0.0, m.width2)) << " px, predicted " << std::sqrt(want2);
  std::printf("edge at %.2f px: width %.3f px (SE of W^2 %.4f), predicted %.3f px\n", edge,
              std::sqrt(std::max(0.0, m.width2)), m.width2_se, std::sqrt(want2));
  return std::sqrt(std::max(0.0, m.width2));
}

}  // namespace nimbus::e2e
