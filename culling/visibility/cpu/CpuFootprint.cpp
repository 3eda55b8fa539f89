#include "culling/visibility/cpu/CpuFootprint.h"

#include <algorithm>
#include <limits>

namespace cdb {

namespace {

constexpr int kFootprintTilePixels = CpuDepthBuffer::kTilePixels;

// The nearer of two stored values in the pass' key order (key = sign * value, smaller is nearer).
inline float nearerValue(float stored, float drawn, bool reversed) {
  return reversed ? std::max(stored, drawn) : std::min(stored, drawn);
}

}  // namespace

float footprintClearValue(const RasterPass& pass) {
  return pass.sign * std::numeric_limits<float>::infinity();
}

void takeFootprint(CpuDepthBuffer& scratch, const RasterPass& pass, CpuFootprint& footprint) {
  footprint.clear();
  const float nothing = footprintClearValue(pass);
  // A write fills only the tiles it reaches; one that it filled but left unchanged holds nothing.
  for (const std::uint32_t t : scratch.materialisedTiles()) {
    const float near = pass.sign > 0 ? scratch.tileMin(t) : scratch.tileMax(t);
    if (near == nothing) continue;
    footprint.tiles.push_back(t);
    footprint.values.insert(footprint.values.end(), scratch.tile(t),
                            scratch.tile(t) + kFootprintTilePixels);
    footprint.nearest.push_back(near);
  }
  scratch.clearMaterialised(nothing);
}

void mergeFootprint(CpuDepthBuffer& buffer, const RasterPass& pass, const CpuFootprint& footprint,
                    RasterWork& work) {
  const bool reversed = pass.sign < 0;
  for (std::size_t i = 0; i < footprint.tiles.size(); ++i) {
    const std::size_t t = footprint.tiles[i];
    // Nothing of the footprint is nearer than the farthest stored value: nothing changes (as
    // the rasteriser's own tile test for writes).
    const float farthest = reversed ? buffer.tileMin(t) : buffer.tileMax(t);
    if (pass.sign * footprint.nearest[i] >= pass.sign * farthest) continue;
    buffer.materialise(t);
    float* stored = buffer.tile(t);
    const float* drawn = footprint.values.data() + i * kFootprintTilePixels;
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (int p = 0; p < kFootprintTilePixels; ++p) {
      const float v = nearerValue(stored[p], drawn[p], reversed);
      stored[p] = v;
      lo = std::min(lo, v), hi = std::max(hi, v);
    }
    buffer.tileMin(t) = lo, buffer.tileMax(t) = hi;
    work.pixelsWritten += kFootprintTilePixels;
  }
}

}  // namespace cdb
