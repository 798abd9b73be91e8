// Motion over the shutter: the shutter's time sampling against its density (chi-square), and keyed
// transforms decomposed and interpolated as Embree interpolates an instance's time steps (T R S, S
// upper triangular, R along the shorter arc).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/motion_transform.hpp"
#include "core/shutter.hpp"

namespace nimbus {
namespace motion_test {

void expect_near(const Transform &a, const Transform &b, float tol) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(a(r, c), b(r, c), tol) << "row " << r << " column " << c;
}

// Chi-square of n samples over `bins` equal bins of [open, close] against the integral of pdf per bin.
double shutter_chi_square(const Shutter &s, int bins, int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<double> observed(size_t(bins), 0.0), expected(size_t(bins), 0.0);
  const double width = (double(s.close()) - s.open()) / bins;
  for (int i = 0; i < n; ++i) {
    const float t = s.sample(u(rng));
    EXPECT_GE(t, s.open());
    EXPECT_LT(t, s.close());
    observed[size_t(std::min(bins - 1, int((t - s.open()) / width)))] += 1;
  }
  for (int b = 0; b < bins; ++b)  // midpoint rule, 64 points per bin
    for (int k = 0; k < 64; ++k)
      expected[size_t(b)] += s.pdf(float(s.open() + width * (b + (k + 0.5) / 64))) * width / 64 * n;
  double chi2 = 0;
  for (size_t b = 0; b < size_t(bins); ++b) {
    if (expected[b] > 0)
      chi2 += (observed[b] - expected[b]) * (observed[b] - expected[b]) / expected[b];
    else
      EXPECT_EQ(observed[b], 0.0) << "a time where the shutter is closed, bin " << b;
  }
  return chi2;
}

TEST(Shutter, SamplesTimesByItsCurve) {
  // A box, a trapezoid (opening and closing ramps) and a curve with a closed stretch in the middle.
  // At most 31 degrees of freedom (bins where the shutter is closed drop out): chi-square above 61.1
  // has probability below 1e-3.
  const Shutter box(0.0f, 0.5f), ramps(1.0f, 2.0f, {{{0, 0}}, {{0.2f, 1}}, {{0.8f, 1}}, {{1, 0}}}),
      gap(-1.0f, 1.0f, {{{0, 1}}, {{0.4f, 1}}, {{0.4f, 0}}, {{0.6f, 0}}, {{0.6f, 2}}, {{1, 2}}});
  for (const Shutter *s : {&box, &ramps, &gap}) {
    double integral = 0;
    for (int k = 0; k < 100000; ++k)
      integral += s->pdf(float(s->open() + (s->close() - s->open()) * (k + 0.5) / 100000)) *
                  (s->close() - s->open()) / 100000;
    EXPECT_NEAR(integral, 1.0, 1e-3);
    EXPECT_LT(shutter_chi_square(*s, 32, 200000, 7), 61.1);
  }
  EXPECT_FLOAT_EQ(box.pdf(0.25f), 2.0f);
  EXPECT_EQ(box.pdf(0.6f), 0.0f);
  EXPECT_EQ(gap.pdf(0.0f), 0.0f) << "closed in the middle";
  EXPECT_NEAR(ramps.pdf(1.5f), 1.0f / 0.8f, 1e-5f);
}

TEST(Shutter, TheBoxDrawsTheTimesOfTheGeneralCurveSolve) {
  // The box takes a shortcut; the same box given with a middle knot takes the general solve, whose
  // segment fractions are exact here (halving and doubling): the times must match bit for bit, up to
  // the last float before the shutter closes.
  const Shutter box(0.1f, 0.35f), knotted(0.1f, 0.35f, {{{0, 1}}, {{0.5f, 1}}, {{1, 1}}});
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int k = 0; k < 10000; ++k) {
    const float v = u(rng);
    ASSERT_EQ(box.sample(v), knotted.sample(v)) << "u = " << v;
  }
  const float last = std::nextafter(1.0f, 0.0f);
  EXPECT_EQ(box.sample(last), knotted.sample(last));
  EXPECT_LT(box.sample(last), 0.35f);
}

TEST(Shutter, InstantaneousSamplesNothing) {
  const Shutter still, at_two(2.0f, 2.0f);
  EXPECT_TRUE(still.instantaneous());
  EXPECT_TRUE(at_two.instantaneous());
  EXPECT_EQ(at_two.sample(0.7f), 2.0f);
  EXPECT_EQ(at_two.pdf(2.0f), 0.0f);
  EXPECT_FALSE(Shutter(0, 1).instantaneous());
}

TEST(MotionTransform, DecompositionRebuildsEveryAffineTransform) {
  const Transform cases[] = {
      Transform::translate({1, -2, 3}) * Transform::rotate(37, {1, 2, 3}) * Transform::scale({2, 0.5f, 3}),
      Transform::rotate(170, {0, 1, 0}) * Transform::scale({-1, 1, 1}),       // a mirror
      Transform({1, 0.4f, 0, 5, 0, 1, 0.3f, 0, 0.2f, 0, 1, -1, 0, 0, 0, 1}),  // shear
      Transform::scale({1e-3f, 1e3f, 1}) * Transform::rotate(-90, {1, 0, 0})};
  for (const Transform &m : cases) {
    const Decomposed d = Decomposed::of(m);
    float largest = 1;
    for (float v : m.matrix()) largest = std::max(largest, std::abs(v));
    expect_near(d.matrix(), m, 1e-5f * largest);
    EXPECT_NEAR(d.rotation.dot(d.rotation), 1.0f, 1e-6f);
  }
}

TEST(MotionTransform, InverseUndoesEveryAffineTransform) {
  const Transform m = Transform::translate({1e3f, -2, 3}) * Transform::rotate(37, {1, 2, 3}) *
                      Transform::scale({-2, 0.5f, 3}) *
                      Transform({1, 0.4f, 0, 5, 0, 1, 0.3f, 0, 0.2f, 0, 1, -1, 0, 0, 0, 1});
  expect_near(m.inverse() * m, Transform{}, 1e-4f);  // float rounding of a translation of 1e3
  expect_near(m * m.inverse(), Transform{}, 1e-3f);  // the translation column carries 1e3
  const Vec3f p(0.3f, -7, 2);
  const Vec3f back = m.inverse().point(m.point(p));
  EXPECT_NEAR(length(back - p), 0.0f, 1e-3f);
}

TEST(MotionTransform, InterpolatesLikeEmbreesTimeSteps) {
  // Two keys over a shutter [0, 2]: a quarter turn about z, a move along x, a growth from 1 to 3.
  const Transform a = Transform::translate({0, 0, 0}), b = Transform::translate({4, 0, 0}) *
                                                           Transform::rotate(90, {0, 0, 1}) *
                                                           Transform::scale(Vec3f(3));
  const MotionTransform m({{0.0f, a}, {2.0f, b}}, 0.0f, 2.0f);
  ASSERT_TRUE(m.moves());
  EXPECT_EQ(m.steps().size(), 2u) << "keys at the shutter's ends are Embree's steps";
  expect_near(m.at(0.0f), a, 1e-5f);
  expect_near(m.at(2.0f), b, 1e-5f);
  // Halfway: 45 degrees (slerp, not the chord), scale 2, translation 2.
  const Vec3f p = m.at(1.0f).point({1, 0, 0});
  EXPECT_NEAR(p.x, 2 + 2 * std::cos(0.25f * 3.14159265f), 1e-4f);
  EXPECT_NEAR(p.y, 2 * std::sin(0.25f * 3.14159265f), 1e-4f);
  // A quarter of the way: 22.5 degrees along the arc (a normalised chord would give 21.6), scale 1.5.
  const Vec3f quarter = m.at(0.5f).point({1, 0, 0});
  EXPECT_NEAR(quarter.x, 1 + 1.5f * std::cos(0.125f * 3.14159265f), 1e-4f);
  EXPECT_NEAR(quarter.y, 1.5f * std::sin(0.125f * 3.14159265f), 1e-4f);
  // Outside the shutter the transform holds still.
  expect_near(m.at(-1.0f), a, 1e-5f);
  expect_near(m.at(3.0f), b, 1e-5f);
  // Keys 270 degrees apart in one step take the shorter arc (90 degrees the other way), as Embree
  // does: the scene parser asks for keys less than 180 degrees apart.
  const MotionTransform turn({{0.0f, a}, {1.0f, Transform::rotate(270, {0, 0, 1})}}, 0.0f, 1.0f);
  const Vec3f q = turn.at(0.5f).point({1, 0, 0});
  EXPECT_NEAR(q.x, std::cos(0.25f * 3.14159265f), 1e-4f);
  EXPECT_NEAR(q.y, -std::sin(0.25f * 3.14159265f), 1e-4f);
}

TEST(MotionTransform, UnevenKeysAreResampledOntoAnEvenGrid) {
  const Transform a, b = Transform::translate({1, 0, 0}), c = Transform::translate({1, 1, 0});
  const MotionTransform m({{0.0f, a}, {0.1f, b}, {1.0f, c}}, 0.0f, 1.0f);
  EXPECT_EQ(m.steps().size(), 41u) << "4 steps in the shortest key interval";
  expect_near(m.at(0.1f), b, 1e-5f);
  expect_near(m.at(0.55f), Transform::translate({1, 0.5f, 0}), 1e-5f);
  // Keys inside the shutter: still before the first and after the last.
  const MotionTransform inside({{0.25f, a}, {0.75f, b}}, 0.0f, 1.0f);
  expect_near(inside.at(0.1f), a, 1e-5f);
  expect_near(inside.at(0.5f), Transform::translate({0.5f, 0, 0}), 1e-5f);
  expect_near(inside.at(0.9f), b, 1e-5f);
  EXPECT_FALSE(MotionTransform(b).moves());
}

}  // namespace motion_test
}  // namespace nimbus
