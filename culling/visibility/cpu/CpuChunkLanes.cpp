// Compiled once per SIMD target (Highway's foreach_target), dispatched at run time.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "culling/visibility/cpu/CpuChunkLanes.cpp"
#include "culling/visibility/cpu/CpuChunkLanes.h"

#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <bit>
#include <cstddef>
#include <limits>

#include "culling/visibility/cpu/CpuLaneOps-inl.h"

HWY_BEFORE_NAMESPACE();
namespace cdb {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using DD = hn::CappedTag<double, 8>;
using VD = hn::Vec<DD>;

// Row r of a screenPoint (CpuPassSpace.h) of corner lanes x, y, z: the same products and sums in
// the same order (x and y rows ((m0 x + m1 y) + m2 z) + m3, the key (m0 x + (m1 y + m2 z)) + m3).
HWY_INLINE VD screenRow(const VD (&m)[4], VD x, VD y, VD z, bool keyRow) {
  if (keyRow)
    return hn::Add(hn::Add(hn::Mul(m[0], x), hn::Add(hn::Mul(m[1], y), hn::Mul(m[2], z))), m[3]);
  return hn::Add(hn::Add(hn::Add(hn::Mul(m[0], x), hn::Mul(m[1], y)), hn::Mul(m[2], z)), m[3]);
}

void GatherChunkInLanes(const float* rows, std::uint32_t count, unsigned parts,
                        const ScreenMatrix& toScreen, const ChunkGather& how, CpuPieces& out) {
  const DD dd;
  const hn::Rebind<float, DD> df;
  const std::size_t lanes = hn::Lanes(dd);
  VD m[3][4];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) m[r][c] = hn::Set(dd, toScreen(r, c));
  const VD wx0 = hn::Set(dd, how.window.x0), wx1 = hn::Set(dd, how.window.x1);
  const VD wy0 = hn::Set(dd, how.window.y0), wy1 = hn::Set(dd, how.window.y1);
  const VD below = hn::Set(dd, -how.marginPx), above = hn::Set(dd, how.marginPx);
  const VD small = hn::Set(dd, static_cast<double>(kSmallBox));
  const VD winding = hn::Set(dd, static_cast<double>(how.winding));
  const VD edgeScale = hn::Set(dd, 1e-9);
  const VD nan = hn::Set(dd, std::numeric_limits<double>::quiet_NaN());
  TriangleExtents& e = out.extents;
  std::size_t kept = 0;
  alignas(64) double corner[3][3][8];  // [axis][corner][lane] of a step needing corners
  alignas(64) double extent[6][8];     // minX, maxX, minY, maxY, minK, maxK of a step's lanes
  for (std::uint32_t part = 0; part < count; part += kPartTriangles) {
    if ((parts >> (part / kPartTriangles) & 1u) == 0) continue;
    const std::uint32_t end = std::min(count, part + kPartTriangles);
    for (std::uint32_t i = part; i < end; i += static_cast<std::uint32_t>(lanes)) {
      VD x[3], y[3], k[3];
      for (int v = 0; v < 3; ++v) {
        const float* at = rows + 3 * v * kChunkTriangles + i;
        const VD px = hn::PromoteTo(dd, hn::LoadU(df, at));
        const VD py = hn::PromoteTo(dd, hn::LoadU(df, at + kChunkTriangles));
        const VD pz = hn::PromoteTo(dd, hn::LoadU(df, at + 2 * kChunkTriangles));
        x[v] = screenRow(m[0], px, py, pz, false);
        y[v] = screenRow(m[1], px, py, pz, false);
        k[v] = screenRow(m[2], px, py, pz, true);
      }
      // std::min({a, b, c}) and std::max({a, b, c}) of the corners: the first of the lowest
      // (highest), as the set-up takes them (raster_detail::smallest, largest).
      const VD minX = lesserOf(lesserOf(x[0], x[1]), x[2]);
      const VD maxX = greaterOf(greaterOf(x[0], x[1]), x[2]);
      const VD minY = lesserOf(lesserOf(y[0], y[1]), y[2]);
      const VD maxY = greaterOf(greaterOf(y[0], y[1]), y[2]);
      // (A non-finite coordinate fails every comparison and is kept: the set-up drops it.)
      auto keep = hn::FirstN(dd, end - i);
      keep = hn::AndNot(hn::Or(hn::Or(hn::Lt(maxX, wx0), hn::Gt(minX, wx1)),
                               hn::Or(hn::Lt(maxY, wy0), hn::Gt(minY, wy1))),
                        keep);
      // Of a solid mesh only the triangles that can decide the command. The mesh's winding number
      // is never of the other sign than `winding` (solidWinding), so along every line of sight
      // the first face crossed enters the solid, turned toward the viewer, and the last leaves
      // it, turned away: in every pixel square, the farthest depth of the mesh over what it
      // covers is reached on a face turned away (what a test needs) and the nearest on one turned
      // toward the viewer (a write). Faces near edge-on (or collapsed) are kept for both: edgeOn
      // lies far above double's rounding of the screen coordinates (2^-50 relative). The screen
      // frame (x, y, key) is right-handed, so a counter-clockwise triangle in x, y faces along
      // +key (facing > 0: turned away from the viewer).
      if (how.winding != 0) {
        const VD e1x = hn::Sub(x[1], x[0]), e1y = hn::Sub(y[1], y[0]);
        const VD e2x = hn::Sub(x[2], x[0]), e2y = hn::Sub(y[2], y[0]);
        const VD facing = hn::Mul(winding, hn::Sub(hn::Mul(e1x, e2y), hn::Mul(e1y, e2x)));
        const VD edgeOn = hn::Mul(hn::Mul(edgeScale, hn::Add(hn::Abs(e1x), hn::Abs(e1y))),
                                  hn::Add(hn::Abs(e2x), hn::Abs(e2y)));
        keep = hn::And(keep, how.test ? hn::Ge(facing, hn::Neg(edgeOn)) : hn::Le(facing, edgeOn));
      }
      const std::size_t n = hn::CountTrue(dd, keep);
      if (n == 0) continue;
      auto finite = hn::FirstN(dd, lanes);
      for (int v = 0; v < 3; ++v)
        finite = hn::And(
            finite, hn::And(hn::IsFinite(x[v]), hn::And(hn::IsFinite(y[v]), hn::IsFinite(k[v]))));
      // (Kept lanes are copied out one by one below: Highway's Compress of doubles copies a
      // 2 KiB index table onto the stack at every call.)
      hn::Store(hn::IfThenElse(finite, minX, nan), dd, extent[0]);
      hn::Store(maxX, dd, extent[1]);
      hn::Store(minY, dd, extent[2]);
      hn::Store(maxY, dd, extent[3]);
      hn::Store(lesserOf(lesserOf(k[0], k[1]), k[2]), dd, extent[4]);
      hn::Store(greaterOf(greaterOf(k[0], k[1]), k[2]), dd, extent[5]);
      // Corners where the set-up may read them: every kept triangle, or those whose pixel box
      // before clipping (the set-up's, firstPixelOf to lastPixelOf) is not small; clipping to the
      // frame only shrinks it.
      auto needs = keep;
      if (!how.everyCorner) {
        const VD w = hn::Sub(lastPixelOf(maxX, above), firstPixelOf(minX, below));
        const VD h = hn::Sub(lastPixelOf(maxY, above), firstPixelOf(minY, below));
        needs = hn::AndNot(hn::And(hn::Lt(w, small), hn::Lt(h, small)), keep);
      }
      std::uint8_t keepBits = 0, needBits = 0;
      hn::StoreMaskBits(dd, keep, &keepBits);
      hn::StoreMaskBits(dd, needs, &needBits);
      if (needBits != 0)
        for (int v = 0; v < 3; ++v) {
          hn::Store(x[v], dd, corner[0][v]);
          hn::Store(y[v], dd, corner[1][v]);
          hn::Store(k[v], dd, corner[2][v]);
        }
      for (unsigned bits = keepBits; bits != 0; bits &= bits - 1) {
        const int lane = std::countr_zero(bits);
        out.offset[kept] = static_cast<std::uint8_t>(i + static_cast<unsigned>(lane));
        e.minX[kept] = extent[0][lane], e.maxX[kept] = extent[1][lane];
        e.minY[kept] = extent[2][lane], e.maxY[kept] = extent[3][lane];
        e.minK[kept] = extent[4][lane], e.maxK[kept] = extent[5][lane];
        if ((needBits >> lane & 1u) != 0) {
          ScreenTriangle& s = out.triangles[kept];
          for (int v = 0; v < 3; ++v)
            s.x[v] = corner[0][v][lane], s.y[v] = corner[1][v][lane], s.k[v] = corner[2][v][lane];
        }
        ++kept;
      }
    }
  }
  if (kept != 0) e.padFrom(kept - 1, (kept + 7) / 8 * 8);
  out.count = kept;
}

}  // namespace HWY_NAMESPACE
}  // namespace cdb
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace cdb {

HWY_EXPORT(GatherChunkInLanes);

void gatherChunkInLanes(const float* rows, std::uint32_t count, unsigned parts,
                        const ScreenMatrix& toScreen, const ChunkGather& how, CpuPieces& out) {
  HWY_DYNAMIC_DISPATCH(GatherChunkInLanes)(rows, count, parts, toScreen, how, out);
}

}  // namespace cdb
#endif
