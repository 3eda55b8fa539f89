#pragma once
// An item's triangles gathered a SIMD step at a time (chunkPieces): their corners read from rows
// (a mesh chunk's own, CpuMeshBounds::chunkCorners, or a list's copy of its triangles') without
// following an index, transformed into the pass' screen space in lanes, bounded, and kept where
// their pixel box can meet the window and they face the command's role. Every value is what the
// same steps one triangle at a time give, bit for bit: the corners' screenPoint (CpuPassSpace.h),
// std::min and std::max over them, the same comparisons.
#include <cstdint>

#include "culling/visibility/cpu/CpuPieces.h"

namespace cdb {

// The window a triangle's extent is kept by (chunkPieces': the tile grown by the margin and half
// a pixel of rounding): kept unless maxX < x0, minX > x1, maxY < y0 or minY > y1.
struct ChunkWindow {
  double x0, x1, y0, y1;
};

// What a chunk's gather keeps and how.
struct ChunkGather {
  ChunkWindow window;
  std::int8_t winding = 0;  // CpuCommand::winding: nonzero keeps only the faces of `test`'s role
  bool test = true;
  double marginPx = 0.0;  // the pass' (RasterPass::marginPx)
  // Corners for every kept triangle; otherwise only for those whose pixel box is not small
  // (smallBox, conservative passes: the others are drawn from their box and key bound alone).
  bool everyCorner = true;
};

// The first `count` triangles of the corner rows at `rows` (kChunkCornerRows rows of
// kChunkTriangles floats; a SIMD step past `count` reads on to the next multiple of 8), in the
// parts whose bit is set in `parts` (part p: triangles [p, p + 1) * kPartTriangles), under
// `toScreen`: those kept, with their extents and offsets, into out (count, triangles, extents,
// offset).
void gatherChunkInLanes(const float* rows, std::uint32_t count, unsigned parts,
                        const ScreenMatrix& toScreen, const ChunkGather& how, CpuPieces& out);

}  // namespace cdb
