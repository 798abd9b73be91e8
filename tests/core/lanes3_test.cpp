// core/lanes3.hpp: every operation gives Vec3f's bits, lane for lane, over magnitudes from 1e-30 to 1e30
// of either sign (signed zeros included), and its loads read exactly three floats.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "core/lanes3.hpp"

namespace nimbus {
namespace lanes3_test {

uint32_t bits(float v) { return std::bit_cast<uint32_t>(v); }

void expect_same(const Vec3f &want, const Lanes3 &got, const char *what) {
  EXPECT_EQ(bits(want.x), bits(got.x())) << what;
  EXPECT_EQ(bits(want.y), bits(got.y())) << what;
  EXPECT_EQ(bits(want.z), bits(got.z())) << what;
}

struct Values {
  std::mt19937 g{11};
  float next() {
    const float exponent = std::uniform_real_distribution<float>(-30, 30)(g);
    const float v = std::pow(10.0f, exponent) * std::uniform_real_distribution<float>(1, 10)(g);
    const uint32_t pick = g() % 16;
    if (pick == 0) return 0.0f;
    if (pick == 1) return -0.0f;
    return pick % 2 ? v : -v;
  }
  Vec3f vec() { return {next(), next(), next()}; }
};

TEST(Lanes3, ArithmeticMatchesVec3fBitForBit) {
  Values values;
  for (int i = 0; i < 20000; ++i) {
    const Vec3f a = values.vec(), b = values.vec();
    const float s = values.next();
    const Lanes3 la = Lanes3::of(a), lb = Lanes3::of(b);
    expect_same(a + b, la + lb, "a + b");
    expect_same(a - b, la - lb, "a - b");
    expect_same(a * b, la * lb, "a * b");
    expect_same(a * s, la * s, "a * s");
    expect_same(-a, -la, "-a");
    expect_same(abs(a), abs(la), "abs");
    expect_same(cross(a, b), cross(la, lb), "cross");
    EXPECT_EQ(bits(dot(a, b)), bits(dot(la, lb))) << "dot";
    EXPECT_EQ(bits(length(a)), bits(length(la))) << "length";
    EXPECT_EQ(bits(max_component(a)), bits(max_component(la))) << "max_component";
    if (length(a) > 0) expect_same(normalize(a), normalize(la), "normalize");
    expect_same(la.vec3(), Lanes3::of(a), "of / vec3");
    if (HasFailure())
      FAIL() << "a " << a.x << " " << a.y << " " << a.z << ", b " << b.x << " " << b.y << " " << b.z << ", s "
             << s;
  }
}

// Each load reads the three floats it is given and no more: the last vector of a heap array, whose
// following bytes AddressSanitizer guards.
TEST(Lanes3, LoadsReadExactlyThreeFloats) {
  const std::vector<float> floats = {1.5f, -2.25f, 0x1p-20f, 7.0f, -0.0f, 3e30f};
  for (const Lanes3 &l : {Lanes3::load(&floats[3]), Lanes3::load_settled(&floats[3])}) {
    EXPECT_EQ(bits(l.x()), bits(7.0f));
    EXPECT_EQ(bits(l.y()), bits(-0.0f));
    EXPECT_EQ(bits(l.z()), bits(3e30f));
    expect_same(Vec3f::load(&floats[3]), l, "load");
  }
}

}  // namespace lanes3_test
}  // namespace nimbus
