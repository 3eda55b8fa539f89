#pragma once
// The CPU depth rasteriser's pixel loops: tests and writes of screen-space triangles (and box faces
// as quads) against the window a CpuDepthBuffer holds, block by block, eight pixels of a block row
// per SIMD step (Google Highway, the best instruction set of the machine chosen at run time).
// Tests and writes walk the same traversal, so they cannot disagree on coverage or block order;
// tests stop at their first occluded sample; block bounds accept or reject whole blocks. A piece
// reaching beyond the window is drawn only inside it, with exactly the coverage and keys it has in
// the whole frame.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "culling/visibility/cpu/CpuDepthBuffer.h"
#include "culling/visibility/cpu/CpuTriangleSetup.h"

namespace cdb {

// Pixels visited, for VisibilityCounters.
struct RasterWork {
  std::uint64_t pixelsTested = 0;
  std::uint64_t pixelsWritten = 0;
  RasterWork& operator+=(const RasterWork& o) {
    pixelsTested += o.pixelsTested, pixelsWritten += o.pixelsWritten;
    return *this;
  }
};

// Bit i of a mask is block i of the buffer's window (CpuDepthBuffer::blockIndex; windows of at
// most 64 blocks, a larger one is drawn whole with kAllBlocks).
using BlockMask = std::uint64_t;
inline constexpr BlockMask kAllBlocks = ~BlockMask{0};

// Blocks of the window whose stored depths a test may not read yet: writes still pending there
// (CpuTileEvaluation) can lie in front of it. Before a test piece reads block i of `blocks`, it
// calls resolve(context, i, zHi) (zHi: the farthest key the piece can test, in the pass' key
// order), which draws there the pending writes that can lie in front of such a key and returns
// whether any is left undrawn there for the test's other pieces; if none, the block leaves the
// mask. Windows of at most 64 blocks.
struct PendingBlocks {
  BlockMask blocks = 0;
  // The blocks the test reads at all (the others were decided before).
  BlockMask read = kAllBlocks;
  bool (*resolve)(void* context, std::size_t block, float zHi) = nullptr;
  void* context = nullptr;
};

// In an order-independent pass (RasterPass::orderIndependent, a buffer with the others' planes)
// every function takes the object whose pieces it draws: a test reads the nearest value any other
// object wrote, a write keeps the nearest value, its object and the others' nearest.

// Tests the triangles (at most kMostTestPieces) in order as one piece; returns the index of the
// first with an occluded sample (at or behind the stored depth), or triangles.size() when the
// piece is fully visible. With `pending`, every triangle against what the buffer holds first and,
// all visible there, every one again in the blocks of pending->read.
inline constexpr std::size_t kMostTestPieces = 64;

// The extent of each of up to kMostTestPieces triangles, made where they are gathered (CpuPieces):
// triangle i's smallest and largest x, y and key (std::min and std::max over its corners in
// order), with minX[i] NaN when one of its nine coordinates is not finite. The set-up's first step
// reads them a row of lanes at a time instead of gathering the corners again; entries past the
// last triangle up to a multiple of 8 repeat it.
struct TriangleExtents {
  alignas(64) double minX[kMostTestPieces], maxX[kMostTestPieces];
  alignas(64) double minY[kMostTestPieces], maxY[kMostTestPieces];
  alignas(64) double minK[kMostTestPieces], maxK[kMostTestPieces];
  // Entry i of each row = entry `last` (the rows read in lanes of up to 8).
  void padFrom(std::size_t last, std::size_t end) {
    for (std::size_t i = last + 1; i < end; ++i)
      minX[i] = minX[last], maxX[i] = maxX[last], minY[i] = minY[last], maxY[i] = maxY[last],
      minK[i] = minK[last], maxK[i] = maxK[last];
  }
};

[[nodiscard]] std::size_t testTrianglesUntilOccluded(
    CpuDepthBuffer& buffer, const RasterPass& pass, std::span<const ScreenTriangle> triangles,
    RasterWork& work, std::uint32_t object = CpuDepthBuffer::kNoObject,
    PendingBlocks* pending = nullptr, const TriangleExtents* extents = nullptr);
// Tests each triangle as its own piece: fullyVisible[i] = 0 where triangle i has an occluded
// sample; triangles whose entry is already 0 are not tested. With `pending`, each is tested
// against what the buffer holds first and, visible there, in the blocks of pending->read.
void testEachTriangle(CpuDepthBuffer& buffer, const RasterPass& pass,
                      std::span<const ScreenTriangle> triangles, std::uint8_t* fullyVisible,
                      RasterWork& work, std::uint32_t object = CpuDepthBuffer::kNoObject,
                      PendingBlocks* pending = nullptr, const TriangleExtents* extents = nullptr);
// The same for quads (ScreenQuad; conservative passes only), each set up and visited as one piece.
[[nodiscard]] std::size_t testQuadsUntilOccluded(CpuDepthBuffer& buffer, const RasterPass& pass,
                                                 std::span<const ScreenQuad> quads,
                                                 RasterWork& work,
                                                 std::uint32_t object = CpuDepthBuffer::kNoObject,
                                                 PendingBlocks* pending = nullptr);

// Writes prepared once and drawn block by block (a write drawn where tests need it, in parts).
// A piece with its pixel box and key bounds set up (step 1), the blocks of the window its box
// reaches, and its coverage (step 2) once a block needed it.
template <class Piece>
struct PreparedWrite {
  TriangleRaster raster;
  BlockMask blocks = 0;
  bool coverage = false;
  Piece piece;  // kept only where step 2 may need it: not for a small piece (smallBox)
};
// The pieces with a pixel in the buffer's window, prepared, into out[0 ..]; returns how many.
// (`extents`: the triangles', at most kMostTestPieces of them.)
std::size_t prepareWrites(const CpuDepthBuffer& buffer, const RasterPass& pass,
                          std::span<const ScreenTriangle> triangles,
                          PreparedWrite<ScreenTriangle>* out,
                          const TriangleExtents* extents = nullptr);
std::size_t prepareWrites(const CpuDepthBuffer& buffer, const RasterPass& pass,
                          std::span<const ScreenQuad> quads, PreparedWrite<ScreenQuad>* out);
// Writes prepared pieces into the blocks of `mask` only: drawn block by block in any order and
// split, they leave what writeTriangles (writeQuads) leaves.
void writePrepared(CpuDepthBuffer& buffer, const RasterPass& pass,
                   std::span<PreparedWrite<ScreenTriangle>> writes, BlockMask mask,
                   RasterWork& work, std::uint32_t object = CpuDepthBuffer::kNoObject);
void writePrepared(CpuDepthBuffer& buffer, const RasterPass& pass,
                   std::span<PreparedWrite<ScreenQuad>> writes, BlockMask mask, RasterWork& work,
                   std::uint32_t object = CpuDepthBuffer::kNoObject);

// Writes the pieces in order, everywhere (depth test "nearer than stored"): prepared and drawn in
// every block, a chunk at a time, in storage the thread keeps (a chunk's worth of set-ups
// constructed at every call would cost more than drawing a few small triangles).
template <class Piece>
void writePieces(CpuDepthBuffer& buffer, const RasterPass& pass, std::span<const Piece> pieces,
                 RasterWork& work, std::uint32_t object = CpuDepthBuffer::kNoObject) {
  constexpr std::size_t kChunk = 64;
  static thread_local std::vector<PreparedWrite<Piece>> prepared(kChunk);
  for (std::size_t at = 0; at < pieces.size(); at += kChunk) {
    const std::size_t n = prepareWrites(
        buffer, pass, pieces.subspan(at, std::min(kChunk, pieces.size() - at)), prepared.data());
    writePrepared(buffer, pass, std::span(prepared.data(), n), kAllBlocks, work, object);
  }
}

// The instruction set the loops run with ("AVX2", "AVX3", "SSE4", ...).
[[nodiscard]] const char* rasteriserTarget();

}  // namespace cdb
