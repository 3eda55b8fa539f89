#pragma once
// A write's footprint: what one depth write leaves in a depth buffer that held nothing, as the
// tiles it reached with its nearest key per pixel. A write keeps, per pixel, the nearer of the
// stored key and each drawn key, whatever the order; so merging the footprint (the nearer of
// stored and footprint, per pixel) leaves exactly what drawing the write again would, at the cost
// of the pixels it covers instead of its triangles' set-up. CpuWriteFootprints decides which
// writes get one.
#include <cstdint>
#include <vector>

#include "culling/visibility/cpu/CpuDepthBuffer.h"
#include "culling/visibility/cpu/CpuRasteriser.h"
#include "culling/visibility/cpu/CpuTriangleSetup.h"

namespace cdb {

struct CpuFootprint {
  // Tiles of the buffer the write changed, each with its 64 stored values (pixels it did not
  // reach hold the "nothing" value, behind every key) and its nearest stored value.
  std::vector<std::uint32_t> tiles;
  std::vector<float> values;
  std::vector<float> nearest;

  void clear() { tiles.clear(), values.clear(), nearest.clear(); }
};

// The stored value a buffer must be cleared to for a footprint: the key behind every other
// (+infinity in the pass' key order).
[[nodiscard]] float footprintClearValue(const RasterPass& pass);

// Moves the tiles of `scratch` that a write reached (cleared to footprintClearValue before it)
// into `footprint`, and clears them again so that `scratch` can take the next write.
void takeFootprint(CpuDepthBuffer& scratch, const RasterPass& pass, CpuFootprint& footprint);

// Draws the write whose footprint this is into `buffer` (the pass' resolution): per pixel, the
// nearer of the stored and the footprint's value; tile bounds stay exact.
void mergeFootprint(CpuDepthBuffer& buffer, const RasterPass& pass, const CpuFootprint& footprint,
                    RasterWork& work);

}  // namespace cdb
