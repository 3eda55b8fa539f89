#pragma once
// The pieces a binned item draws, in its pass' screen space (x, y in pixels, depth key): a chunk
// of a command's triangles (transformed from its mesh's corner rows in SIMD lanes, CpuChunkLanes),
// or one box's faces that decide its answer. Gathered again in every tile that rasterises the
// item; binning itself never transforms a triangle.
#include <array>
#include <cstddef>
#include <cstdint>

#include "culling/visibility/cpu/CpuBins.h"
#include "culling/visibility/cpu/CpuMeshBounds.h"
#include "culling/visibility/cpu/CpuRasteriser.h"
#include "culling/visibility/cpu/CpuRecording.h"
#include "culling/visibility/cpu/CpuTriangleSetup.h"

namespace cdb {

struct CpuPieces {
  std::array<ScreenTriangle, kChunkTriangles> triangles;
  TriangleExtents extents;  // the triangles' (chunkPieces)
  std::array<std::uint8_t, kChunkTriangles> offset;  // triangle i is the item's offset[i]-th
  std::array<ScreenQuad, 6> quads;
  std::size_t count = 0;
  bool areQuads = false;
  bool hasExtents = false;  // `extents` made (chunk pieces)
  [[nodiscard]] const TriangleExtents* extentsIfMade() const {
    return hasExtents ? &extents : nullptr;
  }
};

// The triangles of chunk item `item` (mesh triangles of a Range, entries of the recording's list
// for a Listed command) that its command draws inside `window` (pixels of the frame, in a pass
// whose coverage margin is `marginPx`): of a closed mesh drawn whole only the faces that decide it
// (CpuCommand::winding), and none whose pixel box misses the window (nor any of a part whose
// rectangle misses it: its CpuItemParts); with their extents (out.extents). With `everyCorner`
// false (a conservative pass whose pieces are set up from their extents), a triangle whose pixel
// box is small (smallBox) may be left without its corners: its set-up never reads them.
void chunkPieces(const CpuRun& run, const CpuMeshBounds& bounds, const CpuCommand& c,
                 const CpuItem& item, const PixelRect& window, double marginPx, bool everyCorner,
                 CpuPieces& out);

// A box's matrix from the unit cube [-1, 1]^3 to the screen.
[[nodiscard]] ScreenMatrix cubeToScreen(const ScreenMatrix& objectToScreen, const OrientedBox& box);

// The faces of a box (`cube`: the unit cube's matrix into screen space, CpuBins::boxCubes) that decide
// the answer of a test or the depths of a write (`role`): as quads in conservative passes, as
// triangles in raw ones (whose pixel-centre rule is a triangle's).
void boxPieces(const ScreenMatrix& cube, CpuCommand::Role role, bool conservative,
               CpuPieces& out);

}  // namespace cdb
