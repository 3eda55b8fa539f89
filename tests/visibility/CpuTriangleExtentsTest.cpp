// Triangles set up from their extents (TriangleExtents, made where chunks are gathered) answer and
// prepare exactly as set up from their corners: random batches of small and large triangles, some
// with a coordinate that is not finite, tested each and prepared against random stored depths; and
// as each triangle tested alone, with pending writes resolved on the way.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "culling/visibility/cpu/CpuRasteriser.h"

namespace cdb {
namespace {

// What chunkPieces makes: std::min and std::max over the corners in order, minX NaN where a
// coordinate is not finite, entries past the last up to a multiple of 8 repeating it.
TriangleExtents extentsOf(const std::vector<ScreenTriangle>& triangles) {
  TriangleExtents e;
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const ScreenTriangle& t = triangles[i];
    const bool finite = raster_detail::allFinite(t);
    e.minX[i] =
        finite ? std::min({t.x[0], t.x[1], t.x[2]}) : std::numeric_limits<double>::quiet_NaN();
    e.maxX[i] = std::max({t.x[0], t.x[1], t.x[2]});
    e.minY[i] = std::min({t.y[0], t.y[1], t.y[2]});
    e.maxY[i] = std::max({t.y[0], t.y[1], t.y[2]});
    e.minK[i] = std::min({t.k[0], t.k[1], t.k[2]});
    e.maxK[i] = std::max({t.k[0], t.k[1], t.k[2]});
  }
  if (!triangles.empty()) e.padFrom(triangles.size() - 1, (triangles.size() + 7) / 8 * 8);
  return e;
}

std::vector<ScreenTriangle> randomTriangles(std::mt19937& rng, int resolution, std::size_t n) {
  std::uniform_real_distribution<double> at(-4.0, resolution + 4.0), near(-3.0, 3.0),
      key(0.05, 0.95), unit(0.0, 1.0);
  std::vector<ScreenTriangle> out(n);
  for (ScreenTriangle& t : out) {
    const double cx = at(rng), cy = at(rng), spread = unit(rng) < 0.8 ? 1.0 : 12.0;
    for (int v = 0; v < 3; ++v)
      t.x[v] = cx + spread * near(rng), t.y[v] = cy + spread * near(rng), t.k[v] = key(rng);
    const double odd = unit(rng);
    if (odd < 0.03)
      t.x[1] = std::numeric_limits<double>::quiet_NaN();
    else if (odd < 0.06)
      t.k[2] = std::numeric_limits<double>::infinity();
    else if (odd < 0.08)
      t.y[0] = -std::numeric_limits<double>::infinity();
  }
  return out;
}

void fillRandomly(CpuDepthBuffer& buffer, int resolution, std::mt19937& rng) {
  std::uniform_real_distribution<float> depth(0.f, 1.f);
  buffer.clear(1.f);
  std::vector<ScreenTriangle> occluders = randomTriangles(rng, resolution, 40);
  for (ScreenTriangle& t : occluders)
    for (double& k : t.k) k = std::isfinite(k) ? depth(rng) : k;
  RasterPass pass;
  pass.resolution = resolution;
  pass.marginPx = 1e-6;
  pass.depthEpsilon = 1e-6;
  RasterWork work;
  writePieces(buffer, pass, std::span<const ScreenTriangle>(occluders), work);
}

TEST(CpuTriangleExtents, SetUpAsFromTheCorners) {
  std::mt19937 rng(46);
  for (int round = 0; round < 200; ++round) {
    const int resolution = round % 2 == 0 ? 64 : 128;
    CpuDepthBuffer buffer;
    buffer.place(resolution, 0, 0, resolution / 8, std::min(resolution / 8, 8));
    fillRandomly(buffer, resolution, rng);
    RasterPass pass;
    pass.resolution = resolution;
    pass.marginPx = 1e-6;
    pass.depthEpsilon = 1e-6;
    const std::size_t n = 1 + rng() % kMostTestPieces;
    const std::vector<ScreenTriangle> triangles = randomTriangles(rng, resolution, n);
    const TriangleExtents extents = extentsOf(triangles);

    std::vector<std::uint8_t> fromCorners(n, 1), fromExtents(n, 1);
    for (std::size_t i = 0; i < n; i += 5) fromCorners[i] = fromExtents[i] = 0;  // not asked
    RasterWork a, b;
    testEachTriangle(buffer, pass, triangles, fromCorners.data(), a);
    testEachTriangle(buffer, pass, triangles, fromExtents.data(), b, CpuDepthBuffer::kNoObject,
                     nullptr, &extents);
    ASSERT_EQ(fromCorners, fromExtents) << "round " << round;
    EXPECT_EQ(a.pixelsTested, b.pixelsTested);
    EXPECT_EQ(testTrianglesUntilOccluded(buffer, pass, triangles, a),
              testTrianglesUntilOccluded(buffer, pass, triangles, b, CpuDepthBuffer::kNoObject,
                                         nullptr, &extents));

    std::vector<PreparedWrite<ScreenTriangle>> p(n), q(n);
    const std::size_t m = prepareWrites(buffer, pass, triangles, p.data());
    ASSERT_EQ(prepareWrites(buffer, pass, triangles, q.data(), &extents), m);
    for (std::size_t i = 0; i < m; ++i) {
      const TriangleRaster &r = p[i].raster, &s = q[i].raster;
      EXPECT_EQ(std::tie(r.x0, r.y0, r.x1, r.y1), std::tie(s.x0, s.y0, s.x1, s.y1));
      EXPECT_EQ(std::memcmp(&r.zLo, &s.zLo, sizeof r.zLo), 0);
      EXPECT_EQ(std::memcmp(&r.zHi, &s.zHi, sizeof r.zHi), 0);
      EXPECT_EQ(p[i].blocks, q[i].blocks);
    }
  }
}

// Pending writes for a test to resolve: a block's pending write is a square over the block at a
// depth of its own, drawn the first time a test resolves the block.
struct PendingSquares {
  CpuDepthBuffer* buffer = nullptr;
  RasterPass pass;
  std::vector<float> depthOf;  // per block of the window
  std::vector<bool> drawn;
  static bool resolve(void* context, std::size_t block, float /*zHi*/) {
    auto& p = *static_cast<PendingSquares*>(context);
    if (p.drawn[block]) return false;
    p.drawn[block] = true;
    const int nx = p.buffer->blockX1() - p.buffer->blockX0() + 1;
    const double x = (p.buffer->blockX0() + static_cast<int>(block) % nx) * 8.0 + 4.0;
    const double y = (p.buffer->blockY0() + static_cast<int>(block) / nx) * 8.0 + 4.0;
    const double k = p.depthOf[block];
    const ScreenTriangle t{{x - 3, x + 3, x}, {y - 2, y - 2, y + 3}, {k, k, k}};
    RasterWork work;
    writePieces(*p.buffer, p.pass, std::span<const ScreenTriangle>(&t, 1), work);
    return false;
  }
};

// Tests answering each triangle, set up from extents a batch of lanes at a time: every answer, the
// pixels tested and the pending writes drawn are those of each triangle tested alone (set up on
// its own), in order, with and without pending writes, in a window that is part of the frame.
TEST(CpuTriangleExtents, BatchesAnswerAsEachTriangleAlone) {
  std::mt19937 rng(4646);
  for (int round = 0; round < 300; ++round) {
    const int resolution = 128;
    CpuDepthBuffer buffer;
    buffer.place(resolution, 2 + round % 3, 1, 8, 4 + round % 5);  // at most 64 blocks
    fillRandomly(buffer, resolution, rng);
    RasterPass pass;
    pass.resolution = resolution;
    pass.marginPx = 1e-6;
    pass.depthEpsilon = 1e-6;
    if (round % 4 == 3) {  // a reversed pass: keys are stored values negated
      pass.sign = -1.f, pass.keyLo = -1.f, pass.keyHi = 0.f;
      buffer.clear(1.f);
    }
    const std::size_t n = 1 + rng() % kMostTestPieces;
    std::vector<ScreenTriangle> triangles = randomTriangles(rng, resolution, n);
    for (std::size_t i = 3; i < n; i += 5)  // at the far end, where cleared blocks tie with them
      for (double& k : triangles[i].k) k = 1.0;
    if (pass.sign < 0)
      for (ScreenTriangle& t : triangles)
        for (double& k : t.k) k -= 1.0;
    const TriangleExtents extents = extentsOf(triangles);
    const bool withPending = round % 2 == 1;
    PendingSquares squares;
    squares.pass = pass;
    std::uniform_real_distribution<float> depth(0.f, 1.f);
    for (std::size_t b = 0; b < buffer.blocks(); ++b) squares.depthOf.push_back(depth(rng));
    const BlockMask inWindow =
        buffer.blocks() >= 64 ? kAllBlocks : (BlockMask{1} << buffer.blocks()) - 1;
    const BlockMask reading = withPending ? (BlockMask{rng()} << 32 | rng()) & inWindow : 0;

    CpuDepthBuffer alone = buffer;
    std::vector<std::uint8_t> batched(n, 1), oneByOne(n, 1);
    for (std::size_t i = 0; i < n; i += 7) batched[i] = oneByOne[i] = 0;  // not asked
    RasterWork a, b;
    squares.buffer = &buffer;
    squares.drawn.assign(buffer.blocks(), false);
    PendingBlocks pending{reading, reading, &PendingSquares::resolve, &squares};
    testEachTriangle(buffer, pass, triangles, batched.data(), a, CpuDepthBuffer::kNoObject,
                     withPending ? &pending : nullptr, &extents);
    PendingSquares squaresAlone = squares;
    squaresAlone.buffer = &alone;
    squaresAlone.drawn.assign(alone.blocks(), false);
    PendingBlocks pendingAlone{reading, reading, &PendingSquares::resolve, &squaresAlone};
    for (std::size_t i = 0; i < n; ++i)
      testEachTriangle(alone, pass, std::span<const ScreenTriangle>(&triangles[i], 1), &oneByOne[i],
                       b, CpuDepthBuffer::kNoObject, withPending ? &pendingAlone : nullptr);
    ASSERT_EQ(batched, oneByOne) << "round " << round;
    EXPECT_EQ(a.pixelsTested, b.pixelsTested) << "round " << round;
    EXPECT_EQ(squares.drawn, squaresAlone.drawn) << "round " << round;
  }
}

}  // namespace
}  // namespace cdb
