// The CPU rasteriser's directed rounding of its set-up (double) to the floats its loops use:
// roundUp(v) is the smallest float not below v, roundDown(v) the largest not above it, for random
// doubles over float's whole range and the cases at its edges (zeros, subnormals, halfway values,
// beyond the largest float, infinities). double holds every float exactly, so the comparisons
// below are exact.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "culling/visibility/cpu/CpuTriangleSetup.h"

namespace cdb {
namespace {

using raster_detail::roundDown;
using raster_detail::roundUp;

constexpr float kMax = std::numeric_limits<float>::max();
constexpr double kInf = std::numeric_limits<double>::infinity();

// The smallest float not below v (the largest with `up` false), by stepping from a float near v.
float reference(double v, bool up) {
  if (std::isnan(v)) return static_cast<float>(v);
  if (v > kMax) return up ? std::numeric_limits<float>::infinity() : kMax;
  if (v < -kMax) return up ? -kMax : -std::numeric_limits<float>::infinity();
  float f = static_cast<float>(v);
  const float toward = up ? std::numeric_limits<float>::infinity()
                          : -std::numeric_limits<float>::infinity();
  const float back = -toward;
  if (up ? static_cast<double>(f) < v : static_cast<double>(f) > v) f = std::nextafter(f, toward);
  while (up ? static_cast<double>(std::nextafter(f, back)) >= v
            : static_cast<double>(std::nextafter(f, back)) <= v)
    f = std::nextafter(f, back);
  return f;
}

void expectBoth(double v) {
  const float up = roundUp(v), down = roundDown(v);
  const float wantUp = reference(v, true), wantDown = reference(v, false);
  if (std::isnan(v)) {
    EXPECT_TRUE(std::isnan(up) && std::isnan(down)) << v;
    return;
  }
  // Infinite v stays infinite (the reference above would step off it).
  if (std::isinf(v)) {
    EXPECT_EQ(up, static_cast<float>(v));
    EXPECT_EQ(down, static_cast<float>(v));
    return;
  }
  EXPECT_EQ(up, wantUp) << "roundUp(" << v << ")";
  EXPECT_EQ(down, wantDown) << "roundDown(" << v << ")";
  EXPECT_GE(static_cast<double>(up), v);
  EXPECT_LE(static_cast<double>(down), v);
  // Signed zeros as static_cast<float> leaves them.
  if (v == 0.0) {
    EXPECT_EQ(std::signbit(up), std::signbit(v));
    EXPECT_EQ(std::signbit(down), std::signbit(v));
  }
}

TEST(CpuDirectedRounding, EdgesOfFloatsRange) {
  const double denorm = std::numeric_limits<float>::denorm_min();
  const std::vector<double> cases = {
      0.0, -0.0, denorm, -denorm, denorm / 2, -denorm / 2, denorm * 1.5, 1.0, -1.0,
      1.0 + 0x1p-24,   // halfway between 1 and the next float: rounds to even (down)
      1.0 + 0x1p-23 + 0x1p-24, 1.0 + 0x1p-30, 1.0 - 0x1p-30, kMax, -kMax,
      static_cast<double>(kMax) * (1 + 0x1p-26), -static_cast<double>(kMax) * (1 + 0x1p-26),
      static_cast<double>(kMax) * 2, -static_cast<double>(kMax) * 2, kInf, -kInf,
      std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<float>::min(),
      std::numeric_limits<float>::min() * (1 - 0x1p-30)};
  for (double v : cases) expectBoth(v);
}

TEST(CpuDirectedRounding, RandomDoublesOverFloatsRange) {
  std::mt19937_64 rng(20261124);
  std::uniform_real_distribution<double> mantissa(0.5, 1.0);
  std::uniform_int_distribution<int> exponent(-152, 130);
  int belowItsFloat = 0, aboveItsFloat = 0;
  for (int i = 0; i < 200000; ++i) {
    double v = std::ldexp(mantissa(rng), exponent(rng));
    if (rng() & 1) v = -v;
    // Some values exactly on a float, where both roundings must give that float.
    if (i % 10 == 0) v = static_cast<float>(v);
    const double f = static_cast<float>(v);
    belowItsFloat += f > v, aboveItsFloat += f < v;
    expectBoth(v);
    if (HasFailure()) return;
  }
  // Rounding to nearest went both ways many times: both sides of each select were taken.
  EXPECT_GT(belowItsFloat, 50000);
  EXPECT_GT(aboveItsFloat, 50000);
}

}  // namespace
}  // namespace cdb
