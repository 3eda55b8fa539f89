// A mesh chunk's triangles gathered in SIMD lanes (gatherChunkInLanes, chunkPieces' path for a
// Range item) keep exactly the triangles, offsets, extents and corners of the one-by-one gather
// it replaced, on every SIMD target the machine runs: random chunks (some corners not finite, some
// triangles large, some past the end of the chunk), random matrices, windows and margins, parts
// left out, both roles and every winding. Corners may be left out only where the set-up never
// reads them: a kept triangle whose pixel box is not small (smallBox) has them.
#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "culling/visibility/cpu/CpuChunkLanes.h"
#include "culling/visibility/cpu/CpuPassSpace.h"

namespace cdb {
namespace {

constexpr int kResolution = 128;  // four 64-pixel tiles

// One chunk's corner rows (CpuMeshBounds::chunkCorners' layout): triangles of random size about
// random points of the frame's object space, a few with a coordinate that is not finite, a few
// collapsed to a line or a point (seen edge-on: kept for both roles).
std::vector<float> randomRows(std::mt19937& rng) {
  std::uniform_real_distribution<float> at(-0.1f, 1.1f), near(-0.004f, 0.004f), unit(0.f, 1.f),
      logSpread(-1.f, 4.f);
  std::vector<float> rows(kChunkCornerRows * kChunkTriangles);
  const auto corner = [&](std::uint32_t t, int v, int a) -> float& {
    return rows[(3 * v + a) * kChunkTriangles + t];
  };
  for (std::uint32_t t = 0; t < kChunkTriangles; ++t) {
    // Corners about a pixel from the centre, or up to 40 (boxes of every width near smallBox's).
    const float spread = unit(rng) < 0.5f ? 1.f : std::exp(logSpread(rng));
    const float c[3] = {at(rng), at(rng), at(rng)};
    for (int v = 0; v < 3; ++v)
      for (int a = 0; a < 3; ++a) corner(t, v, a) = c[a] + spread * near(rng);
    const float odd = unit(rng);
    const int v = static_cast<int>(unit(rng) * 2.99f);
    if (odd < 0.03f)
      corner(t, v, 0) = std::numeric_limits<float>::quiet_NaN();
    else if (odd < 0.05f)
      corner(t, v, 2) = std::numeric_limits<float>::infinity();
    else if (odd < 0.10f)
      for (int a = 0; a < 3; ++a) corner(t, 1, a) = corner(t, 0, a);
  }
  return rows;
}

// Triangles of `rows` moved onto the window's edges, for a matrix that maps object x and y to
// kResolution times them (exact): each chosen one's nearest or farthest corner on an axis lands
// exactly on that axis' window bound, where the window test keeps it (or, a quarter pixel
// further out, drops it).
void onWindowEdges(std::vector<float>& rows, const ChunkWindow& w, std::mt19937& rng) {
  std::uniform_real_distribution<float> unit(0.f, 1.f);
  for (std::uint32_t t = 0; t < kChunkTriangles; ++t) {
    if (unit(rng) < 0.5f) continue;
    const int axis = unit(rng) < 0.5f ? 0 : 1;
    const bool low = unit(rng) < 0.5f;  // the window's low bound: the triangle's largest on it
    const double bound = axis == 0 ? (low ? w.x0 : w.x1) : (low ? w.y0 : w.y1);
    const double out = unit(rng) < 0.25f ? (low ? -0.25 : 0.25) : 0.0;
    for (int v = 0; v < 3; ++v) {
      const double step = (low ? -0.5 : 0.5) * v;  // corners at the bound and further out
      rows[(3 * v + axis) * kChunkTriangles + t] =
          static_cast<float>((bound + out + step) / kResolution);
    }
  }
}

// Object space [0, 1]^3 onto the frame, turned a little about each axis (or not at all: x and y
// scaled by kResolution exactly, for onWindowEdges).
ScreenMatrix randomMatrix(std::mt19937& rng, bool turned) {
  std::uniform_real_distribution<double> angle(-0.6, 0.6), shift(-0.05, 0.05);
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  if (turned)
    r = (Eigen::AngleAxisd(angle(rng), Eigen::Vector3d::UnitX()) *
         Eigen::AngleAxisd(angle(rng), Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(angle(rng), Eigen::Vector3d::UnitZ()))
            .toRotationMatrix();
  ScreenMatrix m;
  m.leftCols<3>() = Eigen::Vector3d(kResolution, kResolution, 0.5).asDiagonal() * r;
  m.col(3) = Eigen::Vector3d(turned ? shift(rng) * kResolution : 0.0,
                             turned ? shift(rng) * kResolution : 0.0, 0.25);
  return m;
}

// The one-by-one gather: chunkPieces' loop over a Range item's triangles from their corners'
// screenPoint, the window test on the extent, the faces of the role.
CpuPieces gatheredOneByOne(const std::vector<float>& rows, std::uint32_t count, unsigned parts,
                           const ScreenMatrix& m, const ChunkGather& how) {
  CpuPieces out;
  std::size_t kept = 0;
  TriangleExtents& e = out.extents;
  for (std::uint32_t i = 0; i < count; ++i) {
    if ((parts >> (i / kPartTriangles) & 1u) == 0) continue;
    ScreenTriangle& s = out.triangles[kept];
    for (int v = 0; v < 3; ++v) {
      const ScreenPoint p = screenPoint(m, rows[(3 * v) * kChunkTriangles + i],
                                        rows[(3 * v + 1) * kChunkTriangles + i],
                                        rows[(3 * v + 2) * kChunkTriangles + i]);
      s.x[v] = p.x, s.y[v] = p.y, s.k[v] = p.k;
    }
    const double minX = std::min({s.x[0], s.x[1], s.x[2]});
    const double maxX = std::max({s.x[0], s.x[1], s.x[2]});
    const double minY = std::min({s.y[0], s.y[1], s.y[2]});
    const double maxY = std::max({s.y[0], s.y[1], s.y[2]});
    if (maxX < how.window.x0 || minX > how.window.x1 || maxY < how.window.y0 ||
        minY > how.window.y1)
      continue;
    if (how.winding != 0) {
      const double e1x = s.x[1] - s.x[0], e1y = s.y[1] - s.y[0];
      const double e2x = s.x[2] - s.x[0], e2y = s.y[2] - s.y[0];
      const double facing = how.winding * (e1x * e2y - e1y * e2x);
      const double edgeOn =
          1e-9 * (std::abs(e1x) + std::abs(e1y)) * (std::abs(e2x) + std::abs(e2y));
      if (!(how.test ? facing >= -edgeOn : facing <= edgeOn)) continue;
    }
    e.minX[kept] = raster_detail::allFinite(s) ? minX : std::numeric_limits<double>::quiet_NaN();
    e.maxX[kept] = maxX, e.minY[kept] = minY, e.maxY[kept] = maxY;
    e.minK[kept] = std::min({s.k[0], s.k[1], s.k[2]});
    e.maxK[kept] = std::max({s.k[0], s.k[1], s.k[2]});
    out.offset[kept++] = static_cast<std::uint8_t>(i);
  }
  if (kept != 0) e.padFrom(kept - 1, (kept + 7) / 8 * 8);
  out.count = kept;
  return out;
}

bool sameBits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// Whether the set-up of triangle `t` in a conservative pass with this margin gives a small box.
bool smallWhenSetUp(const ScreenTriangle& t, double marginPx) {
  RasterPass pass;
  pass.resolution = kResolution;
  pass.marginPx = marginPx;
  TriangleRaster r;
  return !setupBounds(t, pass, RasterRole::Test, r) || smallBox(pass, r);
}

// Compares one gather in lanes with the one-by-one gather; returns how many triangles it kept.
std::size_t expectSameGather(const std::vector<float>& rows, std::uint32_t count, unsigned parts,
                             const ScreenMatrix& m, const ChunkGather& how) {
  const CpuPieces want = gatheredOneByOne(rows, count, parts, m, how);
  CpuPieces got;
  gatherChunkInLanes(rows.data(), count, parts, m, how, got);
  EXPECT_EQ(got.count, want.count);
  if (got.count != want.count) return 0;
  const std::size_t padded = (want.count + 7) / 8 * 8;
  for (std::size_t i = 0; i < padded; ++i) {
    SCOPED_TRACE("kept triangle " + std::to_string(i));
    const TriangleExtents& g = got.extents;
    const TriangleExtents& w = want.extents;
    EXPECT_TRUE(sameBits(g.minX[i], w.minX[i]) && sameBits(g.maxX[i], w.maxX[i]) &&
                sameBits(g.minY[i], w.minY[i]) && sameBits(g.maxY[i], w.maxY[i]) &&
                sameBits(g.minK[i], w.minK[i]) && sameBits(g.maxK[i], w.maxK[i]));
    if (i >= want.count) continue;
    EXPECT_EQ(got.offset[i], want.offset[i]);
    const ScreenTriangle& t = want.triangles[i];
    if (how.everyCorner || !smallWhenSetUp(t, how.marginPx)) {
      for (int v = 0; v < 3; ++v) {
        EXPECT_TRUE(sameBits(got.triangles[i].x[v], t.x[v]) &&
                    sameBits(got.triangles[i].y[v], t.y[v]) &&
                    sameBits(got.triangles[i].k[v], t.k[v]))
            << "corner " << v;
      }
    }
  }
  return want.count;
}

TEST(CpuChunkLanes, GatherAsTheOneByOneGatherOnEverySimdTarget) {
  const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  std::size_t kept = 0, dropped = 0;
  for (const std::int64_t target : targets) {
    hwy::SetSupportedTargetsForTest(target);
    SCOPED_TRACE(std::string("target ") + hwy::TargetName(target));
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int round = 0; round < 160; ++round) {
      // A tile of 64 pixels in the frame, grown as chunkPieces grows it (a margin of a sixteenth
      // makes its bounds sixteenths, which the edge rounds' floats hold exactly).
      const bool edges = round % 4 == 1;
      const double marginPx = edges || unit(rng) < 0.5 ? 1.0 / 16.0 : 0.3 * unit(rng);
      const double tx = unit(rng) < 0.5 ? 0.0 : 64.0, ty = unit(rng) < 0.5 ? 0.0 : 64.0;
      ChunkGather how;
      how.window = {tx - marginPx - 0.5, tx + 63 + marginPx + 1.5, ty - marginPx - 0.5,
                    ty + 63 + marginPx + 1.5};
      std::vector<float> rows = randomRows(rng);
      if (edges) onWindowEdges(rows, how.window, rng);
      const ScreenMatrix m = randomMatrix(rng, !edges);
      how.winding = static_cast<std::int8_t>(round % 3 - 1);
      how.test = round % 2 == 0;
      how.marginPx = marginPx;
      how.everyCorner = round % 5 == 0;
      const std::uint32_t count =
          round % 4 == 0 ? 1 + static_cast<std::uint32_t>(unit(rng) * 63) : kChunkTriangles;
      const unsigned parts = round % 3 == 0 ? static_cast<unsigned>(unit(rng) * 16) : 15u;
      SCOPED_TRACE("round " + std::to_string(round));
      const std::size_t n = expectSameGather(rows, count, parts, m, how);
      kept += n;
      dropped += count - n;
    }
  }
  hwy::SetSupportedTargetsForTest(0);
  // Both outcomes met often: the comparison is not of empty gathers.
  EXPECT_GT(kept, 1000u);
  EXPECT_GT(dropped, 1000u);
}

}  // namespace
}  // namespace cdb
