// Compiled once per SIMD target (Highway's foreach_target), dispatched at run time.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "culling/visibility/cpu/CpuRasteriser.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>

#include "culling/visibility/cpu/CpuRasteriser.h"

HWY_BEFORE_NAMESPACE();
namespace cdb {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Eight lanes where the target has them (a tile row in one step), four on SSE4 (two steps).
using D = hn::CappedTag<float, CpuDepthBuffer::kTile>;
constexpr int kTile = CpuDepthBuffer::kTile;

// Stored keys of a tile: its physical bounds in the pass' key order.
struct TileKeys {
  float nearest;
  float farthest;
};
inline TileKeys tileKeys(CpuDepthBuffer& buffer, std::size_t index, float sign) {
  const float lo = buffer.tileMin(index), hi = buffer.tileMax(index);
  return sign > 0 ? TileKeys{lo, hi} : TileKeys{-hi, -lo};
}

// How the triangle covers the pixels of its box inside tile (tx, ty), from the range of each
// edge function over them, evaluated in float like the pixels: None when some edge's range misses
// [lo, hi] (the set-up's tolerance bounds that error too, so no covered pixel is skipped); Whole
// when every edge's range lies within it (where that and a pixel's own evaluation round
// differently at the border, the pixel is taken, which only adds pixels a tolerance's width from
// the triangle); Partial otherwise.
enum class TileCover { None, Partial, Whole };
inline TileCover tileCover(const TriangleRaster& r, int tx, int ty) {
  const float dxA = static_cast<float>(std::max(r.x0, tx * kTile) - r.x0);
  const float dxB = static_cast<float>(std::min(r.x1, tx * kTile + kTile - 1) - r.x0);
  const float dyA = static_cast<float>(std::max(r.y0, ty * kTile) - r.y0);
  const float dyB = static_cast<float>(std::min(r.y1, ty * kTile + kTile - 1) - r.y0);
  TileCover cover = TileCover::Whole;
  for (int e = 0; e < 3; ++e) {
    const float ax = r.a[e] * dxA, bx = r.a[e] * dxB, ay = r.b[e] * dyA, by = r.b[e] * dyB;
    const float fMin = r.c[e] + std::min(ax, bx) + std::min(ay, by);
    const float fMax = r.c[e] + std::max(ax, bx) + std::max(ay, by);
    if (fMax < r.lo[e] || fMin > r.hi[e]) return TileCover::None;
    if (!(fMin >= r.lo[e] && fMax <= r.hi[e])) cover = TileCover::Partial;
  }
  return cover;
}

// The triangle's constants as vectors, in registers for the whole triangle (read through the
// TriangleRaster the compiler would reload them after every store to the depth buffer).
struct Lanes {
  hn::Vec<D> a[3], b[3], c[3], lo[3], hi[3];
  hn::Vec<D> za, zb, zc, zLo, zHi;
};
HWY_INLINE Lanes lanesOf(const TriangleRaster& r) {
  const D d;
  Lanes l;
  for (int e = 0; e < 3; ++e) {
    l.a[e] = hn::Set(d, r.a[e]), l.b[e] = hn::Set(d, r.b[e]), l.c[e] = hn::Set(d, r.c[e]);
    l.lo[e] = hn::Set(d, r.lo[e]), l.hi[e] = hn::Set(d, r.hi[e]);
  }
  l.za = hn::Set(d, r.za), l.zb = hn::Set(d, r.zb), l.zc = hn::Set(d, r.zc);
  l.zLo = hn::Set(d, r.zLo), l.zHi = hn::Set(d, r.zHi);
  return l;
}

// The part of the triangle's pixel box inside tile (tx, ty): its columns (also as dx, for the
// lane masks) and its rows. Tests and writes visit the same pixels.
struct TileSpan {
  int cx0, cx1, ry0, ry1;
  hn::Vec<D> boxLo, boxHi;
  // Whether the step of `n` lanes from tile column `lx` holds a column of the span.
  [[nodiscard]] bool holdsStep(int tx, int lx, int n) const {
    return tx * kTile + lx <= cx1 && tx * kTile + lx + n - 1 >= cx0;
  }
  [[nodiscard]] int columns() const { return cx1 - cx0 + 1; }
};
HWY_INLINE TileSpan spanInTile(const TriangleRaster& r, int tx, int ty) {
  const D d;
  TileSpan s;
  s.cx0 = std::max(r.x0, tx * kTile), s.cx1 = std::min(r.x1, tx * kTile + kTile - 1);
  s.ry0 = std::max(r.y0, ty * kTile), s.ry1 = std::min(r.y1, ty * kTile + kTile - 1);
  s.boxLo = hn::Set(d, static_cast<float>(s.cx0 - r.x0));
  s.boxHi = hn::Set(d, static_cast<float>(s.cx1 - r.x0));
  return s;
}

// Per-row values: the edge and depth functions at the row's dx = 0 (a dx + b dy + c with dy
// fixed).
struct RowSetup {
  hn::Vec<D> base[3];
  hn::Vec<D> zBase;
};
HWY_INLINE void startRow(const Lanes& l, int y, const TriangleRaster& r, RowSetup& row) {
  const D d;
  const auto dy = hn::Set(d, static_cast<float>(y - r.y0));
  for (int e = 0; e < 3; ++e) row.base[e] = hn::MulAdd(l.b[e], dy, l.c[e]);
  row.zBase = hn::MulAdd(l.zb, dy, l.zc);
}

// Covered lanes of one step, given the lanes' dx and the box's columns as dx.
HWY_INLINE hn::Mask<D> covered(const Lanes& l, const RowSetup& row, hn::Vec<D> dx,
                               hn::Vec<D> boxLo, hn::Vec<D> boxHi) {
  auto m = hn::And(hn::Ge(dx, boxLo), hn::Le(dx, boxHi));
  for (int e = 0; e < 3; ++e) {
    const auto f = hn::MulAdd(l.a[e], dx, row.base[e]);
    m = hn::And(m, hn::And(hn::Ge(f, l.lo[e]), hn::Le(f, l.hi[e])));
  }
  return m;
}

// The lanes of one step inside the box's columns (a tile the triangle covers whole).
HWY_INLINE hn::Mask<D> inBox(hn::Vec<D> dx, hn::Vec<D> boxLo, hn::Vec<D> boxHi) {
  return hn::And(hn::Ge(dx, boxLo), hn::Le(dx, boxHi));
}

HWY_INLINE hn::Vec<D> keyAt(const Lanes& l, const RowSetup& row, hn::Vec<D> dx) {
  return hn::Min(hn::Max(hn::MulAdd(l.za, dx, row.zBase), l.zLo), l.zHi);
}

// The SIMD steps of a triangle's span in one tile, row by row: visit(y, lx, dx, row) for each step
// that holds pixels of the span, until it returns true (then true). `pixels` grows by each row's
// pixels.
template <class Visit>
HWY_INLINE bool forEachStep(const Lanes& l, const TriangleRaster& r, const TileSpan& span, int tx,
                            std::uint64_t& pixels, const Visit& visit) {
  const D d;
  const int n = static_cast<int>(hn::Lanes(d));
  RowSetup row;
  for (int y = span.ry0; y <= span.ry1; ++y) {
    startRow(l, y, r, row);
    pixels += static_cast<std::uint64_t>(span.columns());
    for (int lx = 0; lx < kTile; lx += n) {
      if (!span.holdsStep(tx, lx, n)) continue;
      if (visit(y, lx, hn::Iota(d, static_cast<float>(tx * kTile + lx - r.x0)), row)) return true;
    }
  }
  return false;
}

// True when some covered sample is at or behind the stored depth.
bool testOne(CpuDepthBuffer& buffer, const RasterPass& pass, const TriangleRaster& r,
             RasterWork& work) {
  const D d;
  const int tx0 = r.x0 / kTile, tx1 = r.x1 / kTile, ty0 = r.y0 / kTile, ty1 = r.y1 / kTile;
  const bool oneTile = tx0 == tx1 && ty0 == ty1;
  const auto sign = hn::Set(d, pass.sign);
  const Lanes l = lanesOf(r);
  for (int ty = ty0; ty <= ty1; ++ty) {
    for (int tx = tx0; tx <= tx1; ++tx) {
      const std::size_t index = buffer.tileIndex(tx, ty);
      const TileKeys stored = tileKeys(buffer, index, pass.sign);
      // Every sample key is at most zHi: nearer than all the tile holds means visible here.
      if (r.zHi < stored.nearest) continue;
      if (!oneTile && tileCover(r, tx, ty) == TileCover::None) continue;
      // Every sample key is at least zLo: at or behind all the tile holds, so the first covered
      // pixel is occluded without reading depths.
      const bool allBehind = r.zLo >= stored.farthest;
      const bool uniform = buffer.uniform(index);
      const float* values = buffer.tile(index);
      const TileSpan span = spanInTile(r, tx, ty);
      const auto occluded = [&](int y, int lx, hn::Vec<D> dx, const RowSetup& row) HWY_ATTR {
        const auto m = covered(l, row, dx, span.boxLo, span.boxHi);
        if (allBehind) return !hn::AllFalse(d, m);
        const auto key = keyAt(l, row, dx);
        const auto storedKey = uniform
                                   ? hn::Set(d, stored.nearest)
                                   : hn::Mul(hn::LoadU(d, values + (y % kTile) * kTile + lx), sign);
        return !hn::AllFalse(d, hn::And(m, hn::Ge(key, storedKey)));
      };
      if (forEachStep(l, r, span, tx, work.pixelsTested, occluded)) return true;
    }
  }
  return false;
}

// Exact bounds of a tile from its 64 values.
HWY_INLINE void refreshBounds(CpuDepthBuffer& buffer, std::size_t index) {
  const D d;
  const int n = static_cast<int>(hn::Lanes(d));
  const float* values = buffer.tile(index);
  auto lo = hn::LoadU(d, values), hi = lo;
  for (int i = n; i < CpuDepthBuffer::kTilePixels; i += n) {
    const auto v = hn::LoadU(d, values + i);
    lo = hn::Min(lo, v), hi = hn::Max(hi, v);
  }
  buffer.tileMin(index) = hn::GetLane(hn::MinOfLanes(d, lo));
  buffer.tileMax(index) = hn::GetLane(hn::MaxOfLanes(d, hi));
}

// The pixels of the triangle's box in one tile; kWhole: the triangle covers all of them, so
// the edge functions are not evaluated. True when a stored value changed.
template <bool kWhole>
HWY_INLINE bool writeTile(float* values, const Lanes& l, const TriangleRaster& r,
                          const TileSpan& span, int tx, hn::Vec<D> sign, RasterWork& work) {
  const D d;
  bool changed = false;
  forEachStep(l, r, span, tx, work.pixelsWritten,
              [&](int y, int lx, hn::Vec<D> dx, const RowSetup& row) HWY_ATTR {
                const auto m = kWhole ? inBox(dx, span.boxLo, span.boxHi)
                                      : covered(l, row, dx, span.boxLo, span.boxHi);
                float* at = values + (y % kTile) * kTile + lx;
                const auto storedKey = hn::Mul(hn::LoadU(d, at), sign);
                const auto key = keyAt(l, row, dx);
                const auto nearer = hn::And(m, hn::Lt(key, storedKey));
                if (hn::AllFalse(d, nearer)) return false;
                hn::StoreU(hn::Mul(hn::IfThenElse(nearer, key, storedKey), sign), d, at);
                changed = true;
                return false;
              });
  return changed;
}

void writeOne(CpuDepthBuffer& buffer, const RasterPass& pass, const TriangleRaster& r,
              RasterWork& work) {
  const D d;
  const int tx0 = r.x0 / kTile, tx1 = r.x1 / kTile, ty0 = r.y0 / kTile, ty1 = r.y1 / kTile;
  const bool oneTile = tx0 == tx1 && ty0 == ty1;
  const auto sign = hn::Set(d, pass.sign);
  const Lanes l = lanesOf(r);
  for (int ty = ty0; ty <= ty1; ++ty) {
    for (int tx = tx0; tx <= tx1; ++tx) {
      const std::size_t index = buffer.tileIndex(tx, ty);
      // Every written key is at least zLo: nothing in the tile is farther, nothing changes.
      if (r.zLo >= tileKeys(buffer, index, pass.sign).farthest) continue;
      const TileCover cover = tileCover(r, tx, ty);
      if (!oneTile && cover == TileCover::None) continue;
      buffer.materialise(index);
      float* values = buffer.tile(index);
      const TileSpan span = spanInTile(r, tx, ty);
      const bool changed = cover == TileCover::Whole
                               ? writeTile<true>(values, l, r, span, tx, sign, work)
                               : writeTile<false>(values, l, r, span, tx, sign, work);
      // Exact bounds again (a write only lowers keys, but the farthest may drop too, which lets
      // later tests accept the tile whole).
      if (changed) refreshBounds(buffer, index);
    }
  }
}

// A small triangle (smallBox): every pixel of its box, at the key bound of step 1.
bool testSmall(CpuDepthBuffer& buffer, const RasterPass& pass, const TriangleRaster& r,
               RasterWork& work) {
  for (int y = r.y0; y <= r.y1; ++y)
    for (int x = r.x0; x <= r.x1; ++x) {
      const std::size_t index = buffer.tileIndex(x / kTile, y / kTile);
      const TileKeys stored = tileKeys(buffer, index, pass.sign);
      if (r.zHi < stored.nearest) continue;
      ++work.pixelsTested;
      if (buffer.uniform(index) || r.zLo >= stored.farthest) return true;
      const float key = pass.sign * buffer.tile(index)[(y % kTile) * kTile + x % kTile];
      if (r.zHi >= key) return true;
    }
  return false;
}

void writeSmall(CpuDepthBuffer& buffer, const RasterPass& pass, const TriangleRaster& r,
                RasterWork& work) {
  const float value = pass.sign * r.zLo;
  for (int y = r.y0; y <= r.y1; ++y)
    for (int x = r.x0; x <= r.x1; ++x) {
      const std::size_t index = buffer.tileIndex(x / kTile, y / kTile);
      if (r.zLo >= tileKeys(buffer, index, pass.sign).farthest) continue;
      ++work.pixelsWritten;
      buffer.materialise(index);
      float& at = buffer.tile(index)[(y % kTile) * kTile + x % kTile];
      if (!(r.zLo < pass.sign * at)) continue;
      const float old = at;
      at = value;
      // The value only moves toward the near bound; the far bound can only move when the pixel
      // held it.
      if (pass.sign > 0) {
        buffer.tileMin(index) = std::min(buffer.tileMin(index), value);
        if (old == buffer.tileMax(index)) refreshBounds(buffer, index);
      } else {
        buffer.tileMax(index) = std::max(buffer.tileMax(index), value);
        if (old == buffer.tileMin(index)) refreshBounds(buffer, index);
      }
    }
}

// Step 1 of the set-up was enough: every key the test can have is nearer than everything stored
// under its box (visible), or every key a write can have is at or behind it (no change).
bool decidedByTiles(CpuDepthBuffer& buffer, const RasterPass& pass, const TriangleRaster& r,
                    RasterRole role) {
  const int tx0 = r.x0 / kTile, tx1 = r.x1 / kTile, ty0 = r.y0 / kTile, ty1 = r.y1 / kTile;
  for (int ty = ty0; ty <= ty1; ++ty)
    for (int tx = tx0; tx <= tx1; ++tx) {
      const TileKeys stored = tileKeys(buffer, buffer.tileIndex(tx, ty), pass.sign);
      if (role == RasterRole::Test ? r.zHi >= stored.nearest : r.zLo < stored.farthest)
        return false;
    }
  return true;
}

template <class Piece>
HWY_INLINE bool testTriangle(CpuDepthBuffer& buffer, const RasterPass& pass, const Piece& t,
                             RasterWork& work) {
  TriangleRaster r;
  if (!setupBounds(t, pass, RasterRole::Test, r)) return false;
  if (smallBox(pass, r)) return testSmall(buffer, pass, r, work);
  if (decidedByTiles(buffer, pass, r, RasterRole::Test)) return false;
  setupCoverage(t, pass, RasterRole::Test, r);
  return testOne(buffer, pass, r, work);
}

template <class Piece>
std::size_t testUntilOccluded(CpuDepthBuffer& buffer, const RasterPass& pass, const Piece* pieces,
                              std::size_t count, RasterWork& work) {
  for (std::size_t i = 0; i < count; ++i)
    if (testTriangle(buffer, pass, pieces[i], work)) return i;
  return count;
}
std::size_t TestUntilOccluded(CpuDepthBuffer& buffer, const RasterPass& pass,
                              const ScreenTriangle* triangles, std::size_t count,
                              RasterWork& work) {
  return testUntilOccluded(buffer, pass, triangles, count, work);
}
std::size_t TestQuadsUntilOccluded(CpuDepthBuffer& buffer, const RasterPass& pass,
                                   const ScreenQuad* quads, std::size_t count, RasterWork& work) {
  return testUntilOccluded(buffer, pass, quads, count, work);
}

void TestEach(CpuDepthBuffer& buffer, const RasterPass& pass, const ScreenTriangle* triangles,
              std::size_t count, std::uint8_t* fullyVisible, RasterWork& work) {
  for (std::size_t i = 0; i < count; ++i)
    if (testTriangle(buffer, pass, triangles[i], work)) fullyVisible[i] = 0;
}

template <class Piece>
void writeAll(CpuDepthBuffer& buffer, const RasterPass& pass, const Piece* pieces,
              std::size_t count, RasterWork& work) {
  TriangleRaster r;
  for (std::size_t i = 0; i < count; ++i) {
    if (!setupBounds(pieces[i], pass, RasterRole::Write, r)) continue;
    if (smallBox(pass, r)) {
      writeSmall(buffer, pass, r, work);
      continue;
    }
    if (decidedByTiles(buffer, pass, r, RasterRole::Write)) continue;
    setupCoverage(pieces[i], pass, RasterRole::Write, r);
    writeOne(buffer, pass, r, work);
  }
}
void WriteAll(CpuDepthBuffer& buffer, const RasterPass& pass, const ScreenTriangle* triangles,
              std::size_t count, RasterWork& work) {
  writeAll(buffer, pass, triangles, count, work);
}
void WriteQuads(CpuDepthBuffer& buffer, const RasterPass& pass, const ScreenQuad* quads,
                std::size_t count, RasterWork& work) {
  writeAll(buffer, pass, quads, count, work);
}

const char* TargetName() { return hwy::TargetName(HWY_TARGET); }

}  // namespace HWY_NAMESPACE
}  // namespace cdb
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace cdb {

HWY_EXPORT(TestUntilOccluded);
HWY_EXPORT(TestEach);
HWY_EXPORT(WriteAll);
HWY_EXPORT(TestQuadsUntilOccluded);
HWY_EXPORT(WriteQuads);
HWY_EXPORT(TargetName);

std::size_t testTrianglesUntilOccluded(CpuDepthBuffer& buffer, const RasterPass& pass,
                                       std::span<const ScreenTriangle> triangles,
                                       RasterWork& work) {
  return HWY_DYNAMIC_DISPATCH(TestUntilOccluded)(buffer, pass, triangles.data(), triangles.size(),
                                                 work);
}

void testEachTriangle(CpuDepthBuffer& buffer, const RasterPass& pass,
                      std::span<const ScreenTriangle> triangles, std::uint8_t* fullyVisible,
                      RasterWork& work) {
  HWY_DYNAMIC_DISPATCH(TestEach)(buffer, pass, triangles.data(), triangles.size(), fullyVisible,
                                 work);
}

void writeTriangles(CpuDepthBuffer& buffer, const RasterPass& pass,
                    std::span<const ScreenTriangle> triangles, RasterWork& work) {
  HWY_DYNAMIC_DISPATCH(WriteAll)(buffer, pass, triangles.data(), triangles.size(), work);
}

std::size_t testQuadsUntilOccluded(CpuDepthBuffer& buffer, const RasterPass& pass,
                                   std::span<const ScreenQuad> quads, RasterWork& work) {
  return HWY_DYNAMIC_DISPATCH(TestQuadsUntilOccluded)(buffer, pass, quads.data(), quads.size(),
                                                      work);
}

void writeQuads(CpuDepthBuffer& buffer, const RasterPass& pass, std::span<const ScreenQuad> quads,
                RasterWork& work) {
  HWY_DYNAMIC_DISPATCH(WriteQuads)(buffer, pass, quads.data(), quads.size(), work);
}

const char* rasteriserTarget() { return HWY_DYNAMIC_DISPATCH(TargetName)(); }

}  // namespace cdb
#endif
