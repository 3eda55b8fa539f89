#pragma once
// The CPU depth rasteriser's pixel loops: tests and writes of screen-space triangles against a
// CpuDepthBuffer, tile by tile, eight pixels of a tile row per SIMD step (Google Highway, the
// best instruction set of the machine chosen at run time). Tests stop at their first occluded
// sample; tile bounds accept or reject whole tiles.
#include <cstddef>
#include <cstdint>
#include <span>

#include "culling/visibility/cpu/CpuDepthBuffer.h"
#include "culling/visibility/cpu/CpuTriangleSetup.h"

namespace cdb {

// Pixels visited, for VisibilityCounters.
struct RasterWork {
  std::uint64_t pixelsTested = 0;
  std::uint64_t pixelsWritten = 0;
};

// Tests the triangles in order as one piece; returns the index of the first with an occluded
// sample (at or behind the stored depth), or triangles.size() when the piece is fully visible.
[[nodiscard]] std::size_t testTrianglesUntilOccluded(CpuDepthBuffer& buffer,
                                                     const RasterPass& pass,
                                                     std::span<const ScreenTriangle> triangles,
                                                     RasterWork& work);
// Tests each triangle as its own piece: fullyVisible[i] = 0 where triangle i has an occluded
// sample (other entries are left alone).
void testEachTriangle(CpuDepthBuffer& buffer, const RasterPass& pass,
                      std::span<const ScreenTriangle> triangles, std::uint8_t* fullyVisible,
                      RasterWork& work);
// Writes the triangles in order (depth test "nearer than stored").
void writeTriangles(CpuDepthBuffer& buffer, const RasterPass& pass,
                    std::span<const ScreenTriangle> triangles, RasterWork& work);

// The same for quads (ScreenQuad; conservative passes only), each set up and visited as one piece.
[[nodiscard]] std::size_t testQuadsUntilOccluded(CpuDepthBuffer& buffer, const RasterPass& pass,
                                                 std::span<const ScreenQuad> quads,
                                                 RasterWork& work);
void writeQuads(CpuDepthBuffer& buffer, const RasterPass& pass, std::span<const ScreenQuad> quads,
                RasterWork& work);

// The instruction set the loops run with ("AVX2", "AVX3", "SSE4", ...).
[[nodiscard]] const char* rasteriserTarget();

}  // namespace cdb
