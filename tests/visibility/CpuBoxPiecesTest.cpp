// A box's pieces (boxPieces) have their corners bit for bit where screenPoint puts the unit cube's
// corners under the box's matrix: on random matrices (entries of any sign and size, some zero or
// negative zero), for tests and writes, as quads and as triangles. Where the eight corners are
// distinct points, each piece's corners are distinct corners, and a test's and a write's pieces
// together use all eight.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>

#include "culling/visibility/cpu/CpuPassSpace.h"
#include "culling/visibility/cpu/CpuPieces.h"

namespace cdb {
namespace {

using Bits = std::array<std::uint64_t, 3>;

Bits bitsOf(double x, double y, double k) {
  return {std::bit_cast<std::uint64_t>(x), std::bit_cast<std::uint64_t>(y),
          std::bit_cast<std::uint64_t>(k)};
}

ScreenMatrix randomCube(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> scale(-30, 30), kind(0, 9);
  ScreenMatrix m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) {
      const int k = kind(rng);
      m(r, c) = k == 0 ? 0.0 : k == 1 ? -0.0 : std::ldexp(unit(rng), scale(rng));
    }
  return m;
}

// Which of the cube's corners (screenPoint's, bit for bit) a piece's corner is; -1: none.
int cornerOf(const std::array<Bits, 8>& corners, const Bits& point) {
  for (int i = 0; i < 8; ++i)
    if (corners[i] == point) return i;
  return -1;
}

TEST(CpuBoxPieces, CornersAreScreenPointsOfTheUnitCubeBitForBit) {
  std::mt19937 rng(20261201);
  for (int trial = 0; trial < 2000; ++trial) {
    const ScreenMatrix cube = randomCube(rng);
    std::array<Bits, 8> corners;
    for (int i = 0; i < 8; ++i) {
      const ScreenPoint p =
          screenPoint(cube, (i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0);
      corners[i] = bitsOf(p.x, p.y, p.k);
    }
    const bool distinct = std::set<Bits>(corners.begin(), corners.end()).size() == 8;
    for (const bool conservative : {true, false}) {
      std::set<int> used;
      for (const auto role : {CpuCommand::Role::Test, CpuCommand::Role::Write}) {
        CpuPieces pieces;
        boxPieces(cube, role, conservative, pieces);
        ASSERT_EQ(pieces.areQuads, conservative);
        ASSERT_GE(pieces.count, conservative ? 3u : 6u) << "trial " << trial;
        for (std::size_t n = 0; n < pieces.count; ++n) {
          std::set<int> own;
          const int vertices = conservative ? 4 : 3;
          for (int v = 0; v < vertices; ++v) {
            const Bits point =
                conservative
                    ? bitsOf(pieces.quads[n].x[v], pieces.quads[n].y[v], pieces.quads[n].k[v])
                    : bitsOf(pieces.triangles[n].x[v], pieces.triangles[n].y[v],
                             pieces.triangles[n].k[v]);
            const int corner = cornerOf(corners, point);
            ASSERT_GE(corner, 0) << "trial " << trial << ", piece " << n << ", corner " << v;
            own.insert(corner);
            used.insert(corner);
          }
          if (distinct) {
            EXPECT_EQ(own.size(), static_cast<std::size_t>(vertices)) << "trial " << trial;
          }
        }
      }
      if (distinct) {
        EXPECT_EQ(used.size(), 8u) << "trial " << trial;
      }
    }
  }
}

}  // namespace
}  // namespace cdb
