// Compiled once per SIMD target (Highway's foreach_target), dispatched at run time.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "culling/visibility/cpu/CpuRasteriser.cpp"
#include "culling/visibility/cpu/CpuRasteriser.h"

#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "culling/visibility/cpu/CpuLaneOps-inl.h"

HWY_BEFORE_NAMESPACE();
namespace cdb {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Eight lanes where the target has them (a block row in one step), four on SSE4 (two steps).
using D = hn::CappedTag<float, CpuDepthBuffer::kBlock>;
constexpr int kBlock = CpuDepthBuffer::kBlock;
constexpr bool kTest = true;

constexpr auto blockOf = CpuDepthBuffer::blockOf;  // (pixel boxes are clipped to the frame)
constexpr auto inBlock = CpuDepthBuffer::inBlock;

// Stored keys of a block: its bounds in the pass' key order.
using BlockKeys = CpuDepthBuffer::BlockKeys;

// Whether a block's stored keys leave nothing to do: every key a test can have is nearer than all
// of them (visible there), or every key a write can have is at or behind all of them (no change).
template <bool kIsTest>
inline bool blockDecides(const TriangleRaster& r, const BlockKeys& stored) {
  return kIsTest ? r.zHi < stored.nearest : r.zLo >= stored.farthest;
}

// What a small test (smallBox) learns from a block's stored keys before reading its pixels: its
// keys decide it (nothing stored in front), it is occluded at its first pixel (the block is
// uniform, or everything stored lies at or in front of the test's nearest key), or its pixels
// must be read.
enum class SmallTestInBlock { Decided, Occluded, ReadPixels };
inline SmallTestInBlock smallTestInBlock(const CpuDepthBuffer& buffer, std::size_t index,
                                         const TriangleRaster& r, const BlockKeys& stored) {
  if (blockDecides<true>(r, stored)) return SmallTestInBlock::Decided;
  return buffer.uniform(index) || r.zLo >= stored.farthest ? SmallTestInBlock::Occluded
                                                            : SmallTestInBlock::ReadPixels;
}

// Whether block `index` of the window is in `mask` (masks cover windows of up to 64 blocks; a
// larger window is drawn whole, with kAllBlocks).
inline bool inMask(BlockMask mask, std::size_t index) {
  return index >= 64 || ((mask >> index) & 1u) != 0;
}

// Whether block `index` still has writes pending that a test may read (PendingBlocks).
inline bool unresolved(const PendingBlocks* pending, std::size_t index) {
  return pending != nullptr && index < 64 && ((pending->blocks >> index) & 1u) != 0;
}

// The part of the triangle's pixel box inside block (bx, by), as offsets from the box's corner
// (x0, y0): columns dxA..dxB, rows dyA..dyB.
struct BoxInBlock {
  int dxA, dxB, dyA, dyB;
};
inline BoxInBlock boxInBlock(const TriangleRaster& r, int bx, int by) {
  return {std::max(r.x0, bx * kBlock) - r.x0, std::min(r.x1, bx * kBlock + kBlock - 1) - r.x0,
          std::max(r.y0, by * kBlock) - r.y0, std::min(r.y1, by * kBlock + kBlock - 1) - r.y0};
}

// Before a test piece reads block `index`: the pending writes that can lie in front of it there
// (nearest key at most `zHi`, the farthest key its pixels there can have) drawn there.
inline void resolveBlock(PendingBlocks* pending, std::size_t index, float zHi) {
  if (!unresolved(pending, index)) return;
  if (!pending->resolve(pending->context, index, zHi)) pending->blocks &= ~(BlockMask{1} << index);
}

// The farthest key a pixel of the triangle's box inside block (bx, by) can have: its depth plane
// is largest over a rectangle at a corner, evaluated in double with room for the float
// evaluation's rounding (keyAt: two fused multiply-adds), and clamped like a key. Tighter than zHi
// where a face spans many blocks at a slant, so fewer pending writes are drawn for it.
inline float farthestKeyIn(const TriangleRaster& r, int bx, int by) {
  const BoxInBlock o = boxInBlock(r, bx, by);
  const double zx = std::max(double{r.za} * o.dxA, double{r.za} * o.dxB);
  const double zy = std::max(double{r.zb} * o.dyA, double{r.zb} * o.dyB);
  const double plane = r.zc + zx + zy;
  const double rounding = 1e-6 * (std::abs(double{r.zc}) + std::abs(zx) + std::abs(zy));
  const double key = std::clamp(plane + rounding, double{r.zLo}, double{r.zHi});
  return raster_detail::nextUp(static_cast<float>(key));  // (key is finite)
}

// The blocks of the triangle's pixel box inside the buffer's window (inclusive; empty when the
// box misses it).
struct BlockRange {
  int x0, y0, x1, y1;
};
inline BlockRange blocksInWindow(const CpuDepthBuffer& buffer, const TriangleRaster& r) {
  return {std::max(blockOf(r.x0), buffer.blockX0()), std::max(blockOf(r.y0), buffer.blockY0()),
          std::min(blockOf(r.x1), buffer.blockX1()), std::min(blockOf(r.y1), buffer.blockY1())};
}
// The same, only the rows and columns that hold a block of `mask` (a piece drawn in a few blocks
// of its box does not walk the others).
inline BlockRange blocksInMask(const CpuDepthBuffer& buffer, const TriangleRaster& r,
                               BlockMask mask) {
  BlockRange range = blocksInWindow(buffer, r);
  const int nx = buffer.blockX1() - buffer.blockX0() + 1;
  if (mask == kAllBlocks || buffer.blocks() > 64 || nx >= 64) return range;
  if (mask == 0) return {range.x0, range.y0, range.x0 - 1, range.y0 - 1};
  // (A tile of 64 pixels has rows of 8 blocks: a shift then, not a division.)
  const auto rowOf = [nx](int index) { return nx == 8 ? index >> 3 : index / nx; };
  const int rowLo = rowOf(std::countr_zero(mask)), rowHi = rowOf(63 - std::countl_zero(mask));
  BlockMask columns = 0;
  for (int row = rowLo; row <= rowHi; ++row) columns |= mask >> (row * nx);
  columns &= (BlockMask{1} << nx) - 1;
  const int colLo = std::countr_zero(columns), colHi = 63 - std::countl_zero(columns);
  range.x0 = std::max(range.x0, buffer.blockX0() + colLo);
  range.x1 = std::min(range.x1, buffer.blockX0() + colHi);
  range.y0 = std::max(range.y0, buffer.blockY0() + rowLo);
  range.y1 = std::min(range.y1, buffer.blockY0() + rowHi);
  return range;
}

// How the triangle covers the pixels of its box inside block (bx, by), from the range of each
// edge function over them, evaluated in float like the pixels: None when some edge's range misses
// [lo, hi] (the set-up's tolerance bounds that error too, so no covered pixel is skipped); Whole
// when every edge's range lies within it (where that and a pixel's own evaluation round
// differently at the border, a write takes the pixel, which only adds pixels a tolerance's width
// from the triangle); Partial otherwise.
enum class BlockCover { None, Partial, Whole };
#if HWY_TARGET == HWY_SCALAR
inline BlockCover blockCover(const TriangleRaster& r, int bx, int by) {
  const BoxInBlock o = boxInBlock(r, bx, by);
  const float dxA = static_cast<float>(o.dxA), dxB = static_cast<float>(o.dxB);
  const float dyA = static_cast<float>(o.dyA), dyB = static_cast<float>(o.dyB);
  BlockCover cover = BlockCover::Whole;
  for (int e = 0; e < 3; ++e) {
    const float ax = r.a[e] * dxA, bx2 = r.a[e] * dxB, ay = r.b[e] * dyA, by2 = r.b[e] * dyB;
    const float fMin = r.c[e] + std::min(ax, bx2) + std::min(ay, by2);
    const float fMax = r.c[e] + std::max(ax, bx2) + std::max(ay, by2);
    if (fMax < r.lo[e] || fMin > r.hi[e]) return BlockCover::None;
    if (!(fMin >= r.lo[e] && fMax <= r.hi[e])) cover = BlockCover::Partial;
  }
  return cover;
}
#else
// (With four lanes: the three edges in the lanes of one vector, each lane computing what the
// scalar expressions above compute, in the same order; a fourth lane of zeros decides nothing.
// Each edge array is followed by more of the set-up, which the fourth lane reads and zeroes.)
using D4 = hn::FixedTag<float, 4>;
static_assert(offsetof(TriangleRaster, hi) + 4 * sizeof(float) <= sizeof(TriangleRaster));
HWY_INLINE hn::Vec<D4> edgeLanes(const float (&v)[3]) {
  const D4 d;
  return hn::IfThenElseZero(hn::FirstN(d, 3), hn::LoadU(d, v));
}
inline BlockCover blockCover(const TriangleRaster& r, int bx, int by) {
  const D4 d;
  const BoxInBlock o = boxInBlock(r, bx, by);
  const auto a = edgeLanes(r.a), b = edgeLanes(r.b), c = edgeLanes(r.c);
  const auto ax = hn::Mul(a, hn::Set(d, static_cast<float>(o.dxA)));
  const auto bx2 = hn::Mul(a, hn::Set(d, static_cast<float>(o.dxB)));
  const auto ay = hn::Mul(b, hn::Set(d, static_cast<float>(o.dyA)));
  const auto by2 = hn::Mul(b, hn::Set(d, static_cast<float>(o.dyB)));
  const auto fMin = hn::Add(hn::Add(c, lesserOf(ax, bx2)), lesserOf(ay, by2));
  const auto fMax = hn::Add(hn::Add(c, greaterOf(ax, bx2)), greaterOf(ay, by2));
  const auto lo = edgeLanes(r.lo), hi = edgeLanes(r.hi);
  if (!hn::AllFalse(d, hn::Or(hn::Lt(fMax, lo), hn::Gt(fMin, hi)))) return BlockCover::None;
  return hn::AllTrue(d, hn::And(hn::Ge(fMin, lo), hn::Le(fMax, hi))) ? BlockCover::Whole
                                                                      : BlockCover::Partial;
}
#endif

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

// The part of the triangle's pixel box inside block (bx, by): its columns (also as dx, for the
// lane masks) and its rows.
struct BlockSpan {
  int cx0, cx1, ry0, ry1;
  hn::Vec<D> boxLo, boxHi;
  // Whether the step of `n` lanes from block column `lx` holds a column of the span.
  [[nodiscard]] bool holdsStep(int bx, int lx, int n) const {
    return bx * kBlock + lx <= cx1 && bx * kBlock + lx + n - 1 >= cx0;
  }
  [[nodiscard]] int columns() const { return cx1 - cx0 + 1; }
};
HWY_INLINE BlockSpan spanInBlock(const TriangleRaster& r, int bx, int by) {
  const D d;
  BlockSpan s;
  s.cx0 = std::max(r.x0, bx * kBlock), s.cx1 = std::min(r.x1, bx * kBlock + kBlock - 1);
  s.ry0 = std::max(r.y0, by * kBlock), s.ry1 = std::min(r.y1, by * kBlock + kBlock - 1);
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

// The lanes of one step inside the box's columns.
HWY_INLINE hn::Mask<D> inBox(hn::Vec<D> dx, const BlockSpan& span) {
  return hn::And(hn::Ge(dx, span.boxLo), hn::Le(dx, span.boxHi));
}

// Covered lanes of one step, given the lanes' dx.
HWY_INLINE hn::Mask<D> covered(const Lanes& l, const RowSetup& row, hn::Vec<D> dx,
                               const BlockSpan& span) {
  auto m = inBox(dx, span);
  for (int e = 0; e < 3; ++e) {
    const auto f = hn::MulAdd(l.a[e], dx, row.base[e]);
    m = hn::And(m, hn::And(hn::Ge(f, l.lo[e]), hn::Le(f, l.hi[e])));
  }
  return m;
}

HWY_INLINE hn::Vec<D> keyAt(const Lanes& l, const RowSetup& row, hn::Vec<D> dx) {
  return hn::Min(hn::Max(hn::MulAdd(l.za, dx, row.zBase), l.zLo), l.zHi);
}

// The SIMD steps of a triangle's span in one block, row by row: visit(y, lx, dx, row) for each
// step that holds pixels of the span, until it returns true (then true). `pixels` grows by each
// row's pixels.
template <class Visit>
HWY_INLINE bool forEachStep(const Lanes& l, const TriangleRaster& r, const BlockSpan& span, int bx,
                            std::uint64_t& pixels, const Visit& visit) {
  const D d;
  const int n = static_cast<int>(hn::Lanes(d));
  // Each step's dx (lane i: its column - x0): Iota's lanes, made once (Iota builds them lane by
  // lane), plus the step's first, both exact in float.
  const auto lane = hn::Iota(d, 0.f);
  hn::Vec<D> dx[kBlock];
  bool holds[kBlock];
  for (int lx = 0; lx < kBlock; lx += n) {
    holds[lx] = span.holdsStep(bx, lx, n);
    dx[lx] = hn::Add(hn::Set(d, static_cast<float>(bx * kBlock + lx - r.x0)), lane);
  }
  RowSetup row;
  for (int y = span.ry0; y <= span.ry1; ++y) {
    startRow(l, y, r, row);
    pixels += static_cast<std::uint64_t>(span.columns());
    for (int lx = 0; lx < kBlock; lx += n)
      if (holds[lx] && visit(y, lx, dx[lx], row)) return true;
  }
  return false;
}

// Exact bounds of a block from its 64 values (kOthers: the nearest of the first plane and the
// farthest of the second, see CpuDepthBuffer).
template <bool kOthers>
HWY_INLINE void refreshBounds(CpuDepthBuffer& buffer, std::size_t index) {
  const D d;
  const int n = static_cast<int>(hn::Lanes(d));
  const float* values = buffer.block(index);
  const float* far = kOthers ? buffer.others(index) : values;
  auto lo = hn::LoadU(d, values), hi = hn::LoadU(d, far);
  for (int i = n; i < CpuDepthBuffer::kBlockPixels; i += n) {
    lo = hn::Min(lo, hn::LoadU(d, values + i));
    hi = hn::Max(hi, hn::LoadU(d, far + i));
  }
  buffer.blockMin(index) = hn::GetLane(hn::MinOfLanes(d, lo));
  buffer.blockMax(index) = hn::GetLane(hn::MaxOfLanes(d, hi));
}

// The object of the pieces drawn, and its lanes, for an order-independent pass (kOthers).
using DI = hn::RebindToSigned<D>;
struct Writer {
  std::uint32_t object;
  hn::Vec<DI> lanes;
};
HWY_INLINE Writer writerOf(std::uint32_t object) {
  return {object, hn::Set(DI(), static_cast<std::int32_t>(object))};
}
HWY_INLINE hn::Mask<D> ownLanes(const std::uint32_t* objects, const Writer& w) {
  const auto ids = hn::LoadU(DI(), reinterpret_cast<const std::int32_t*>(objects));
  return hn::RebindMask(D(), hn::Eq(ids, w.lanes));
}

// The keys a test reads in the step at `at` of a non-uniform block `index`: the stored values in
// the pass' key order, or (kOthers, sign +1) at a pixel its own object wrote nearest, the nearest
// of the others.
template <bool kOthers>
HWY_INLINE hn::Vec<D> readKeys(const CpuDepthBuffer& buffer, std::size_t index, int at,
                               hn::Vec<D> sign, const Writer& writer) {
  const D d;
  const auto values = hn::LoadU(d, buffer.block(index) + at);
  if constexpr (kOthers)
    return hn::IfThenElse(ownLanes(buffer.objects(index) + at, writer),
                          hn::LoadU(d, buffer.others(index) + at), values);
  else
    return hn::Mul(values, sign);
}

// An order-independent write of `key` into the lanes `m` of the step at `at` of block `index`: per
// pixel, a key of the object that wrote the nearest value lowers it; a nearer key of another
// object takes it over (the old nearest becomes the nearest of the others); a farther one lowers
// the others' nearest. True when a stored value changed.
HWY_INLINE bool writeOthersStep(CpuDepthBuffer& buffer, std::size_t index, int at, hn::Mask<D> m,
                                hn::Vec<D> key, const Writer& writer) {
  const D d;
  float* values = buffer.block(index) + at;
  float* othersAt = buffer.others(index) + at;
  const auto nearest = hn::LoadU(d, values);
  const auto others = hn::LoadU(d, othersAt);
  const auto own = ownLanes(buffer.objects(index) + at, writer);
  // Nearer than the nearest: the key is the nearest now, of this object.
  const auto nearer = hn::And(m, hn::Lt(key, nearest));
  const auto takeOver = hn::AndNot(own, nearer);
  const auto lowersOthers = hn::And(hn::AndNot(own, hn::AndNot(nearer, m)), hn::Lt(key, others));
  if (hn::AllFalse(d, hn::Or(nearer, lowersOthers))) return false;
  hn::StoreU(hn::IfThenElse(nearer, key, nearest), d, values);
  hn::StoreU(hn::IfThenElse(takeOver, nearest, hn::IfThenElse(lowersOthers, key, others)), d,
             othersAt);
  auto* ids = reinterpret_cast<std::int32_t*>(buffer.objects(index) + at);
  hn::StoreU(hn::IfThenElse(hn::RebindMask(DI(), takeOver), writer.lanes, hn::LoadU(DI(), ids)),
             DI(), ids);
  return true;
}

// A test of the span in one block: true at the first covered sample at or behind the stored key
// (kOthers: the nearest any other object wrote).
template <bool kOthers>
HWY_INLINE bool testBlock(const CpuDepthBuffer& buffer, std::size_t index, const BlockKeys& stored,
                          const Lanes& l, const TriangleRaster& r, const BlockSpan& span, int bx,
                          hn::Vec<D> sign, const Writer& writer, RasterWork& work) {
  const D d;
  // Every sample key is at least zLo: at or behind all the block holds, so the first covered
  // pixel is occluded without reading depths.
  const bool allBehind = r.zLo >= stored.farthest;
  const bool uniform = buffer.uniform(index);
  return forEachStep(l, r, span, bx, work.pixelsTested,
                     [&](int y, int lx, hn::Vec<D> dx, const RowSetup& row) HWY_ATTR {
                       const auto m = covered(l, row, dx, span);
                       if (allBehind) return !hn::AllFalse(d, m);
                       const auto key = keyAt(l, row, dx);
                       const int at = inBlock(y) * kBlock + lx;
                       const auto storedKey =
                           uniform ? hn::Set(d, stored.nearest)
                                   : readKeys<kOthers>(buffer, index, at, sign, writer);
                       return !hn::AllFalse(d, hn::And(m, hn::Ge(key, storedKey)));
                     });
}

// A write of the span in one block; kWhole: the triangle covers the whole box there, so the edge
// functions are not evaluated. True when a stored value changed. kOthers: per pixel, a key of the
// object that wrote the nearest value lowers it; a nearer key of another object takes it over
// (the old nearest becomes the nearest of the others); a farther one lowers the others' nearest.
template <bool kWhole, bool kOthers>
HWY_INLINE bool writeBlock(CpuDepthBuffer& buffer, std::size_t index, const Lanes& l,
                           const TriangleRaster& r, const BlockSpan& span, int bx, hn::Vec<D> sign,
                           const Writer& writer, RasterWork& work) {
  const D d;
  float* values = buffer.block(index);
  bool changed = false;
  // (Lanes nearer than stored, over every step: a branch per step on whether any is mispredicts
  // as often as a step's pixels are nearer or not.)
  auto anyNearer = hn::FirstN(d, 0);
  forEachStep(l, r, span, bx, work.pixelsWritten,
              [&](int y, int lx, hn::Vec<D> dx, const RowSetup& row) HWY_ATTR {
                const auto m = kWhole ? inBox(dx, span) : covered(l, row, dx, span);
                const int at = inBlock(y) * kBlock + lx;
                const auto key = keyAt(l, row, dx);
                if constexpr (kOthers) {
                  if (!writeOthersStep(buffer, index, at, m, key, writer)) return false;
                } else {
                  const auto storedKey = hn::Mul(hn::LoadU(d, values + at), sign);
                  const auto nearer = hn::And(m, hn::Lt(key, storedKey));
                  // Stored back whatever it holds: the lanes not nearer keep their value (times the
                  // sign twice, exact).
                  hn::StoreU(hn::Mul(hn::IfThenElse(nearer, key, storedKey), sign), d, values + at);
                  anyNearer = hn::Or(anyNearer, nearer);
                  return false;
                }
                changed = true;
                return false;
              });
  return changed || !hn::AllFalse(d, anyNearer);
}

// The one traversal of a triangle's blocks inside the window, for tests and writes alike: blocks
// whose bounds decide it are skipped, blocks it misses are skipped, the rest are visited. A test
// returns true at its first occluded sample.
template <bool kIsTest, bool kOthers>
bool drawBlocks(CpuDepthBuffer& buffer, const RasterPass& pass, const TriangleRaster& r,
                BlockMask mask, const Writer& writer, RasterWork& work,
                PendingBlocks* pending = nullptr) {
  const D d;
  const bool oneBlock = blockOf(r.x0) == blockOf(r.x1) && blockOf(r.y0) == blockOf(r.y1);
  const auto sign = hn::Set(d, pass.sign);
  const Lanes l = lanesOf(r);
  const BlockRange blocks = blocksInMask(buffer, r, mask);
  for (int by = blocks.y0; by <= blocks.y1; ++by) {
    for (int bx = blocks.x0; bx <= blocks.x1; ++bx) {
      const std::size_t index = buffer.blockIndex(bx, by);
      if (!inMask(mask, index)) continue;
      if constexpr (kIsTest) {
        if (unresolved(pending, index)) {
          // Writes are drawn only where the piece has pixels.
          if (!oneBlock && blockCover(r, bx, by) == BlockCover::None) continue;
          resolveBlock(pending, index, farthestKeyIn(r, bx, by));
        }
      }
      const BlockKeys stored = buffer.blockKeys(index, pass.sign);
      if (blockDecides<kIsTest>(r, stored)) continue;
      // A test of a triangle inside one block needs no cover: its pixels are all there is.
      const BlockCover cover = kIsTest && oneBlock ? BlockCover::Partial : blockCover(r, bx, by);
      if (!oneBlock && cover == BlockCover::None) continue;
      const BlockSpan span = spanInBlock(r, bx, by);
      if constexpr (kIsTest) {
        if (testBlock<kOthers>(buffer, index, stored, l, r, span, bx, sign, writer, work))
          return true;
      } else {
        buffer.materialise(index);
        const bool changed =
            cover == BlockCover::Whole
                ? writeBlock<true, kOthers>(buffer, index, l, r, span, bx, sign, writer, work)
                : writeBlock<false, kOthers>(buffer, index, l, r, span, bx, sign, writer, work);
        // Exact bounds again (a write only lowers keys, but the farthest may drop too, which
        // lets later tests accept the block whole).
        if (changed) refreshBounds<kOthers>(buffer, index);
      }
    }
  }
  return false;
}

// The pixels [x0, x1] x [y0, y1] of a small triangle's box inside block `index` (at most
// kSmallBox columns), tested or written at its key bound, a row of the block per SIMD step (lanes
// outside the columns masked): what testing (writing) them one by one in row order does, with the
// same pixel counts (a test counts up to its first occluded pixel) and the same block bounds after
// a write (made exact once at the end when a changed pixel held the far bound, or in an
// order-independent pass when any changed: the values that remaking them after each such pixel
// leaves). A test returns true at an occluded pixel.
template <bool kIsTest, bool kOthers>
HWY_INLINE bool smallInBlock(CpuDepthBuffer& buffer, std::size_t index, const RasterPass& pass,
                             const TriangleRaster& r, int x0, int x1, int y0, int y1,
                             const Writer& writer, RasterWork& work) {
  const D d;
  const int n = static_cast<int>(hn::Lanes(d));
  const int c0 = inBlock(x0), c1 = inBlock(x1);
  const auto sign = hn::Set(d, pass.sign);
  float* values = buffer.block(index);
  // Key bound of step 1 (a write stores it as a value of the pass' sign).
  const float value = pass.sign * r.zLo;
  auto changed = hn::FirstN(d, 0), heldFar = hn::FirstN(d, 0);
  bool othersChanged = false;
  const float far = pass.sign > 0 ? buffer.blockMax(index) : buffer.blockMin(index);
  for (int y = y0; y <= y1; ++y)
    for (int lx = c0 - c0 % n; lx <= c1; lx += n) {
      const int from = std::max(c0, lx) - lx, to = std::min(c1, lx + n - 1) - lx;
      const auto columns = hn::AndNot(hn::FirstN(d, static_cast<std::size_t>(from)),
                                      hn::FirstN(d, static_cast<std::size_t>(to + 1)));
      const int at = inBlock(y) * kBlock + lx;
      if constexpr (kIsTest) {
        const auto key = readKeys<kOthers>(buffer, index, at, sign, writer);
        const std::intptr_t first =
            hn::FindFirstTrue(d, hn::And(columns, hn::Ge(hn::Set(d, r.zHi), key)));
        if (first >= 0) {
          work.pixelsTested += static_cast<std::uint64_t>(first - from + 1);
          return true;
        }
        work.pixelsTested += static_cast<std::uint64_t>(to - from + 1);
      } else if constexpr (kOthers) {
        work.pixelsWritten += static_cast<std::uint64_t>(to - from + 1);
        othersChanged =
            writeOthersStep(buffer, index, at, columns, hn::Set(d, value), writer) || othersChanged;
      } else {
        work.pixelsWritten += static_cast<std::uint64_t>(to - from + 1);
        const auto stored = hn::LoadU(d, values + at);
        const auto nearer = hn::And(columns, hn::Lt(hn::Set(d, r.zLo), hn::Mul(sign, stored)));
        hn::StoreU(hn::IfThenElse(nearer, hn::Set(d, value), stored), d, values + at);
        changed = hn::Or(changed, nearer);
        heldFar = hn::Or(heldFar, hn::And(nearer, hn::Eq(stored, hn::Set(d, far))));
      }
    }
  if constexpr (kOthers && !kIsTest) {
    if (othersChanged) refreshBounds<true>(buffer, index);
  } else if constexpr (!kIsTest) {
    if (hn::AllFalse(d, changed)) return false;
    // The value only moves toward the near bound; the far bound can only move when a changed
    // pixel held it.
    if (pass.sign > 0)
      buffer.blockMin(index) = std::min(buffer.blockMin(index), value);
    else
      buffer.blockMax(index) = std::max(buffer.blockMax(index), value);
    if (!hn::AllFalse(d, heldFar)) refreshBounds<false>(buffer, index);
  }
  return false;
}

// A small triangle (smallBox): every pixel of its box inside the window, at the key bound of
// step 1 (zHi for a test, zLo for a write), block by block (a box of a few pixels mostly lies in
// one block: its pending writes, bounds and storage are looked at once).
template <bool kIsTest, bool kOthers>
bool drawSmall(CpuDepthBuffer& buffer, const RasterPass& pass, const TriangleRaster& r,
               BlockMask mask, const Writer& writer, RasterWork& work,
               PendingBlocks* pending = nullptr) {
  const BlockRange blocks = blocksInWindow(buffer, r);
  for (int by = blocks.y0; by <= blocks.y1; ++by)
    for (int bx = blocks.x0; bx <= blocks.x1; ++bx) {
      const std::size_t index = buffer.blockIndex(bx, by);
      if (!inMask(mask, index)) continue;
      if constexpr (kIsTest) {
        resolveBlock(pending, index, r.zHi);
        const SmallTestInBlock found =
            smallTestInBlock(buffer, index, r, buffer.blockKeys(index, pass.sign));
        if (found == SmallTestInBlock::Decided) continue;
        if (found == SmallTestInBlock::Occluded) {
          ++work.pixelsTested;
          return true;
        }
      } else {
        if (blockDecides<kIsTest>(r, buffer.blockKeys(index, pass.sign))) continue;
        buffer.materialise(index);
      }
      const BoxInBlock o = boxInBlock(r, bx, by);
      if (smallInBlock<kIsTest, kOthers>(buffer, index, pass, r, r.x0 + o.dxA, r.x0 + o.dxB,
                                         r.y0 + o.dyA, r.y0 + o.dyB, writer, work))
        return true;
    }
  return false;
}

// Step 1 of the set-up was enough: the window's blocks under the box decide the piece (a block
// with writes still pending decides nothing).
template <bool kIsTest>
bool decidedByBlocks(const CpuDepthBuffer& buffer, const RasterPass& pass, const TriangleRaster& r,
                     BlockMask mask, const PendingBlocks* pending = nullptr) {
  const BlockRange blocks = blocksInMask(buffer, r, mask);
  for (int by = blocks.y0; by <= blocks.y1; ++by)
    for (int bx = blocks.x0; bx <= blocks.x1; ++bx) {
      const std::size_t index = buffer.blockIndex(bx, by);
      if (!inMask(mask, index)) continue;
      if (unresolved(pending, index)) return false;
      if (!blockDecides<kIsTest>(r, buffer.blockKeys(index, pass.sign))) return false;
    }
  return true;
}

// A piece whose bounds are set up (setupBounds) drawn in the blocks of `mask`: small, decided by
// the blocks, or set up whole (`coverage` says whether it is already) and drawn.
template <bool kIsTest, bool kOthers, class Piece>
HWY_INLINE bool drawSetUp(CpuDepthBuffer& buffer, const RasterPass& pass, const Piece& t,
                          TriangleRaster& r, bool& coverage, BlockMask mask, const Writer& writer,
                          RasterWork& work, PendingBlocks* pending) {
  if (smallBox(pass, r)) {
    if constexpr (kIsTest && !kOthers) {
      // Most small tests lie in one block, which its keys decide (nothing stored in front: not
      // occluded there) or which is occluded at once (uniform, or everything stored at or in front
      // of the test): drawSmall's steps for that block, without the call. The rest (pixels to
      // read, pending writes to resolve first, several blocks) goes to drawSmall. (In an
      // order-independent pass most tests read their block's pixels: not worth the look.)
      const int bx = blockOf(r.x0), by = blockOf(r.y0);
      if (bx == blockOf(r.x1) && by == blockOf(r.y1)) {
        if (bx < buffer.blockX0() || bx > buffer.blockX1() || by < buffer.blockY0() ||
            by > buffer.blockY1())
          return false;
        const std::size_t index = buffer.blockIndex(bx, by);
        if (!inMask(mask, index)) return false;
        if (!unresolved(pending, index)) {
          const SmallTestInBlock found =
              smallTestInBlock(buffer, index, r, buffer.blockKeys(index, pass.sign));
          if (found == SmallTestInBlock::Decided) return false;
          if (found == SmallTestInBlock::Occluded) {
            ++work.pixelsTested;
            return true;
          }
        }
      }
    }
    return drawSmall<kIsTest, kOthers>(buffer, pass, r, mask, writer, work, pending);
  }
  if (decidedByBlocks<kIsTest>(buffer, pass, r, mask, pending)) return false;
  if (!coverage) setupCoverage(t, pass, kIsTest ? RasterRole::Test : RasterRole::Write, r);
  coverage = true;
  return drawBlocks<kIsTest, kOthers>(buffer, pass, r, mask, writer, work, pending);
}

// Step 1 of the set-up (setupBounds) for several pieces at a time, one per lane of doubles: the
// same operations in the same order on the same values (IEEE arithmetic, ceil and floor are exact,
// min and max select as std::min and std::max do, float rounding and its nudges by the bits as
// roundUp), so every box and key bound is bit for bit setupBounds'. Conservative passes only (raw
// mode's zero-area test is left to setupBounds).
using DD = hn::CappedTag<double, 8>;
constexpr std::size_t kMostLanes = 8;
struct BatchBounds {
  std::int32_t x0[kMostLanes], y0[kMostLanes], x1[kMostLanes], y1[kMostLanes];
  float zLo[kMostLanes], zHi[kMostLanes];
  std::uint8_t ok[kMostLanes];
};
// raster_detail::roundUp, lane by lane: the float's bits, and the next float's, as exact doubles.
HWY_INLINE hn::Vec<hn::Rebind<float, DD>> roundUpLanes(hn::Vec<DD> v) {
  const DD dd;
  const hn::Rebind<float, DD> df;
  const hn::Rebind<std::int32_t, DD> di;
  const auto f = hn::DemoteTo(df, v);
  const auto below = hn::Lt(hn::PromoteTo(dd, f), v);
  const auto bits = hn::PromoteTo(dd, hn::BitCast(di, f));
  const auto zero = hn::Or(hn::Eq(bits, hn::Zero(dd)), hn::Eq(bits, hn::Set(dd, -2147483648.0)));
  const auto step = hn::IfThenElse(hn::Lt(bits, hn::Zero(dd)), hn::Set(dd, -1.0), hn::Set(dd, 1.0));
  const auto up = hn::IfThenElse(zero, hn::Set(dd, 1.0), hn::Add(bits, step));
  return hn::BitCast(df, hn::DemoteTo(di, hn::IfThenElse(below, up, bits)));
}
template <class V>
HWY_INLINE V clampLanes(V v, V lo, V hi) {  // std::clamp(v, lo, hi)
  return hn::IfThenElse(hn::Lt(v, lo), lo, hn::IfThenElse(hn::Lt(hi, v), hi, v));
}
// The boxes and key bounds of a batch from its pieces' extents (smallest and largest x, y and key
// per lane; `finite`: the lanes whose coordinates all are).
template <class Mask>
HWY_INLINE void boundsFromExtents(hn::Vec<DD> minX, hn::Vec<DD> maxX, hn::Vec<DD> minY,
                                  hn::Vec<DD> maxY, hn::Vec<DD> kMin, hn::Vec<DD> kMax,
                                  Mask finite, const RasterPass& pass, RasterRole role,
                                  BatchBounds& out) {
  const DD dd;
  const hn::Rebind<float, DD> df;
  const hn::Rebind<std::int32_t, DD> di;
  const double m = pass.marginPx;
  const auto one = hn::Set(dd, 1.0);
  const auto below = hn::Set(dd, -m), above = hn::Set(dd, m);
  auto bx0 = firstPixelOf(minX, below), by0 = firstPixelOf(minY, below);
  auto bx1 = lastPixelOf(maxX, above), by1 = lastPixelOf(maxY, above);
  const auto last = hn::Set(dd, static_cast<double>(pass.resolution - 1));
  bx0 = greaterOf(bx0, hn::Zero(dd)), by0 = greaterOf(by0, hn::Zero(dd));
  bx1 = lesserOf(bx1, last), by1 = lesserOf(by1, last);
  const auto ok = hn::And(finite, hn::And(hn::Le(bx0, bx1), hn::Le(by0, by1)));
  hn::StoreU(hn::DemoteTo(di, bx0), di, out.x0);
  hn::StoreU(hn::DemoteTo(di, by0), di, out.y0);
  hn::StoreU(hn::DemoteTo(di, bx1), di, out.x1);
  hn::StoreU(hn::DemoteTo(di, by1), di, out.y1);
  const bool test = role == RasterRole::Test;
  const auto shift = hn::Set(dd, test ? pass.depthEpsilon : -pass.depthEpsilon);
  const auto keyLo = hn::Set(df, pass.keyLo), keyHi = hn::Set(df, pass.keyHi);
  if (test) {
    hn::StoreU(clampLanes(roundUpLanes(hn::Add(kMin, shift)), keyLo, keyHi), df, out.zLo);
    hn::StoreU(clampLanes(roundUpLanes(hn::Add(kMax, shift)), keyLo, keyHi), df, out.zHi);
  } else {  // roundDown(v) = -roundUp(-v)
    hn::StoreU(clampLanes(hn::Neg(roundUpLanes(hn::Neg(hn::Add(kMin, shift)))), keyLo, keyHi), df,
               out.zLo);
    hn::StoreU(clampLanes(hn::Neg(roundUpLanes(hn::Neg(hn::Add(kMax, shift)))), keyLo, keyHi), df,
               out.zHi);
  }
  const hn::Rebind<std::uint8_t, DD> d8;
  hn::StoreU(hn::DemoteTo(d8, hn::DemoteTo(di, hn::IfThenElseZero(ok, one))), d8, out.ok);
}

// Pieces [first, first + lanes) of `pieces` (`count` in all; lanes past the last repeat it), their
// corners gathered.
template <class Piece>
HWY_INLINE void boundsBatch(const Piece* pieces, std::size_t first, std::size_t count,
                            const RasterPass& pass, RasterRole role, BatchBounds& out) {
  const DD dd;
  const hn::RebindToSigned<DD> di64;
  constexpr std::int64_t kStride = sizeof(Piece) / sizeof(double);
  static_assert(sizeof(Piece) == 3 * Piece::kVertices * sizeof(double));
  const auto lane = hn::Iota(di64, 0);
  const auto lastLane = hn::Set(di64, static_cast<std::int64_t>(count - 1 - first));
  const auto index = hn::Mul(hn::Min(lane, lastLane), hn::Set(di64, kStride));
  const double* base = &pieces[first].x[0];
  hn::Vec<DD> minX, maxX, minY, maxY, kMin, kMax;
  auto finite = hn::Eq(hn::Zero(dd), hn::Zero(dd));
  for (int v = 0; v < Piece::kVertices; ++v) {
    const auto x = hn::GatherIndex(dd, base + v, index);
    const auto y = hn::GatherIndex(dd, base + Piece::kVertices + v, index);
    const auto k = hn::GatherIndex(dd, base + 2 * Piece::kVertices + v, index);
    finite = hn::And(finite, hn::And(hn::IsFinite(x), hn::And(hn::IsFinite(y), hn::IsFinite(k))));
    if (v == 0) {
      minX = maxX = x, minY = maxY = y, kMin = kMax = k;
    } else {
      minX = lesserOf(minX, x), maxX = greaterOf(maxX, x);
      minY = lesserOf(minY, y), maxY = greaterOf(maxY, y);
      kMin = lesserOf(kMin, k), kMax = greaterOf(kMax, k);
    }
  }
  boundsFromExtents(minX, maxX, minY, maxY, kMin, kMax, finite, pass, role, out);
}

// The same from the triangles' extents (TriangleExtents), read in rows: minX is NaN where a
// coordinate is not finite.
HWY_INLINE void boundsBatch(const TriangleExtents& e, std::size_t first, const RasterPass& pass,
                            RasterRole role, BatchBounds& out) {
  const DD dd;
  const auto minX = hn::Load(dd, e.minX + first), maxX = hn::Load(dd, e.maxX + first);
  const auto minY = hn::Load(dd, e.minY + first), maxY = hn::Load(dd, e.maxY + first);
  const auto kMin = hn::Load(dd, e.minK + first), kMax = hn::Load(dd, e.maxK + first);
  boundsFromExtents(minX, maxX, minY, maxY, kMin, kMax, hn::Not(hn::IsNaN(minX)), pass, role,
                    out);
}

// setupBounds of pieces[0 .. count) one after another, set up a batch of lanes at a time for the
// triangles of a chunk in a conservative pass: next(i, r) sets up piece i (in order, each once)
// into r. (A box's few faces, and a few triangles, are set up one by one: a batch's gathers cost
// more than the set-ups they would share.)
template <class Piece>
class BoundsInBatches {
 public:
  // With `extents` (triangles only), batches read them instead of the corners, at any count.
  BoundsInBatches(const Piece* pieces, std::size_t count, const RasterPass& pass, RasterRole role,
                  const TriangleExtents* extents = nullptr)
      : pieces_(pieces), count_(count), pass_(pass), role_(role), extents_(extents),
        batched_(pass.conservative && Piece::kVertices == 3 &&
                 (count >= kLeastBatched || extents != nullptr)) {}
  HWY_INLINE bool next(std::size_t i, TriangleRaster& r) {
    if (!batched_) return setupBounds(pieces_[i], pass_, role_, r);
    if (i >= end_) {
      // (Extents are read in aligned rows: a batch starts at a multiple of the lane count, and
      // the rows are padded to a multiple of 8.)
      const std::size_t lanes = hn::Lanes(DD());
      begin_ = extents_ != nullptr ? i - i % lanes : i;
      end_ = std::min(count_, begin_ + lanes);
      if (extents_ != nullptr)
        boundsBatch(*extents_, begin_, pass_, role_, batch_);
      else
        boundsBatch(pieces_, i, count_, pass_, role_, batch_);
    }
    const std::size_t at = i - begin_;
    r.x0 = batch_.x0[at], r.y0 = batch_.y0[at], r.x1 = batch_.x1[at], r.y1 = batch_.y1[at];
    r.zLo = batch_.zLo[at], r.zHi = batch_.zHi[at];
    return batch_.ok[at] != 0;
  }

 private:
  const Piece* pieces_;
  std::size_t count_;
  const RasterPass& pass_;
  RasterRole role_;
  const TriangleExtents* extents_;
  static constexpr std::size_t kLeastBatched = 8;
  bool batched_;
  std::size_t begin_ = 0, end_ = 0;
  BatchBounds batch_;
};

// Pieces prepared to be written later, block by block: those with a pixel in the window.
template <class Piece>
std::size_t prepare(const CpuDepthBuffer& buffer, const RasterPass& pass, const Piece* pieces,
                    std::size_t count, PreparedWrite<Piece>* out,
                    const TriangleExtents* extents = nullptr) {
  std::size_t n = 0;
  BoundsInBatches<Piece> bounds(pieces, count, pass, RasterRole::Write, extents);
  for (std::size_t i = 0; i < count; ++i) {
    PreparedWrite<Piece>& w = out[n];
    if (!bounds.next(i, w.raster)) continue;
    const BlockRange blocks = blocksInWindow(buffer, w.raster);
    if (blocks.x0 > blocks.x1 || blocks.y0 > blocks.y1) continue;
    w.blocks = 0;
    if (blocks.x0 == blocks.x1 && blocks.y0 == blocks.y1) {  // (most pieces: one block)
      const std::size_t index = buffer.blockIndex(blocks.x0, blocks.y0);
      w.blocks = index < 64 ? BlockMask{1} << index : kAllBlocks;
    } else {
      for (int by = blocks.y0; by <= blocks.y1; ++by)
        for (int bx = blocks.x0; bx <= blocks.x1; ++bx) {
          const std::size_t index = buffer.blockIndex(bx, by);
          w.blocks |= index < 64 ? BlockMask{1} << index : kAllBlocks;
        }
    }
    w.coverage = false;
    // (A small piece is drawn from its box and key bound alone, drawSetUp: its corners are not
    // kept.)
    if (!smallBox(pass, w.raster)) w.piece = pieces[i];
    ++n;
  }
  return n;
}
std::size_t PrepareTriangles(const CpuDepthBuffer& buffer, const RasterPass& pass,
                             const ScreenTriangle* triangles, std::size_t count,
                             PreparedWrite<ScreenTriangle>* out, const TriangleExtents* extents) {
  return prepare(buffer, pass, triangles, count, out, extents);
}
std::size_t PrepareQuads(const CpuDepthBuffer& buffer, const RasterPass& pass,
                         const ScreenQuad* quads, std::size_t count,
                         PreparedWrite<ScreenQuad>* out) {
  return prepare(buffer, pass, quads, count, out);
}

template <bool kOthers, class Piece>
void writePreparedPieces(CpuDepthBuffer& buffer, const RasterPass& pass,
                         PreparedWrite<Piece>* writes, std::size_t count, BlockMask mask,
                         const Writer& writer, RasterWork& work) {
  for (std::size_t i = 0; i < count; ++i) {
    PreparedWrite<Piece>& w = writes[i];
    if ((w.blocks & mask) != 0)
      drawSetUp<!kTest, kOthers>(buffer, pass, w.piece, w.raster, w.coverage, mask, writer, work,
                                 nullptr);
  }
}

// The pieces (at most kMostTestPieces) tested in order as one piece, up to the first with an
// occluded sample. With `pending`, in two rounds that share each piece's set-up: every piece
// against what the buffer holds, then, all visible there, every piece again in the blocks of
// pending->read, resolving them (one occluded in the first round leaves the pending writes
// undrawn). With `each`, every piece is its own test (each[i] cleared when occluded; a piece
// whose entry is 0 is not tested), both rounds piece by piece, as without `pending`.
template <bool kOthers, class Piece>
std::size_t testUntilOccluded(CpuDepthBuffer& buffer, const RasterPass& pass, const Piece* pieces,
                              std::size_t count, const Writer& writer, RasterWork& work,
                              PendingBlocks* pending, std::uint8_t* each,
                              const TriangleExtents* extents = nullptr) {
  BoundsInBatches<Piece> bounds(pieces, count, pass, RasterRole::Test, extents);
  if (each != nullptr || pending == nullptr) {
    // (Every field a piece's drawing reads is set by its own set-up first: one for all of them.)
    TriangleRaster r;
    for (std::size_t i = 0; i < count; ++i) {
      bool coverage = false;
      if ((each == nullptr || each[i]) && bounds.next(i, r) &&
          (drawSetUp<kTest, kOthers>(buffer, pass, pieces[i], r, coverage, kAllBlocks, writer, work,
                                     nullptr) ||
           (pending && drawSetUp<kTest, kOthers>(buffer, pass, pieces[i], r, coverage,
                                                 pending->read, writer, work, pending)))) {
        if (each == nullptr) return i;
        each[i] = 0;
      }
    }
    return count;
  }
  // Uninitialised: set-ups are written before they are read.
  alignas(TriangleRaster) unsigned char storage[kMostTestPieces * sizeof(TriangleRaster)];
  auto* kept = reinterpret_cast<TriangleRaster*>(storage);
  bool setUp[kMostTestPieces], coverage[kMostTestPieces];
  for (std::size_t i = 0; i < count; ++i) {
    setUp[i] = bounds.next(i, *std::construct_at(kept + i));
    coverage[i] = false;
    if (setUp[i] && drawSetUp<kTest, kOthers>(buffer, pass, pieces[i], kept[i], coverage[i],
                                              kAllBlocks, writer, work, nullptr))
      return i;
  }
  for (std::size_t i = 0; i < count; ++i)
    if (setUp[i] && drawSetUp<kTest, kOthers>(buffer, pass, pieces[i], kept[i], coverage[i],
                                              pending->read, writer, work, pending))
      return i;
  return count;
}

// The exported entry points: kOthers chosen by the pass.
#define CDB_WITH_OTHERS(call, ...) \
  (pass.orderIndependent ? call<true>(__VA_ARGS__) : call<false>(__VA_ARGS__))
void WritePreparedTriangles(CpuDepthBuffer& buffer, const RasterPass& pass,
                            PreparedWrite<ScreenTriangle>* writes, std::size_t count,
                            BlockMask mask, std::uint32_t object, RasterWork& work) {
  CDB_WITH_OTHERS(writePreparedPieces, buffer, pass, writes, count, mask, writerOf(object), work);
}
void WritePreparedQuads(CpuDepthBuffer& buffer, const RasterPass& pass,
                        PreparedWrite<ScreenQuad>* writes, std::size_t count, BlockMask mask,
                        std::uint32_t object, RasterWork& work) {
  CDB_WITH_OTHERS(writePreparedPieces, buffer, pass, writes, count, mask, writerOf(object), work);
}
std::size_t TestUntilOccluded(CpuDepthBuffer& buffer, const RasterPass& pass,
                              const ScreenTriangle* triangles, std::size_t count,
                              std::uint32_t object, RasterWork& work, PendingBlocks* pending,
                              std::uint8_t* each, const TriangleExtents* extents) {
  return CDB_WITH_OTHERS(testUntilOccluded, buffer, pass, triangles, count, writerOf(object), work,
                         pending, each, extents);
}
std::size_t TestQuadsUntilOccluded(CpuDepthBuffer& buffer, const RasterPass& pass,
                                   const ScreenQuad* quads, std::size_t count, std::uint32_t object,
                                   RasterWork& work, PendingBlocks* pending) {
  return CDB_WITH_OTHERS(testUntilOccluded, buffer, pass, quads, count, writerOf(object), work,
                         pending, nullptr);
}
#undef CDB_WITH_OTHERS

const char* TargetName() { return hwy::TargetName(HWY_TARGET); }

}  // namespace HWY_NAMESPACE
}  // namespace cdb
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace cdb {

HWY_EXPORT(TestUntilOccluded);
HWY_EXPORT(TestQuadsUntilOccluded);
HWY_EXPORT(PrepareTriangles);
HWY_EXPORT(PrepareQuads);
HWY_EXPORT(WritePreparedTriangles);
HWY_EXPORT(WritePreparedQuads);
HWY_EXPORT(TargetName);

namespace {
// A test of more pieces than testUntilOccluded keeps set-ups for is refused.
void checkTestSize(std::size_t pieces) {
  if (pieces > kMostTestPieces)
    throw std::invalid_argument("a test of " + std::to_string(pieces) + " pieces: at most " +
                                std::to_string(kMostTestPieces));
}
}  // namespace

std::size_t testTrianglesUntilOccluded(CpuDepthBuffer& buffer, const RasterPass& pass,
                                       std::span<const ScreenTriangle> triangles, RasterWork& work,
                                       std::uint32_t object, PendingBlocks* pending,
                                       const TriangleExtents* extents) {
  checkTestSize(triangles.size());
  return HWY_DYNAMIC_DISPATCH(TestUntilOccluded)(buffer, pass, triangles.data(), triangles.size(),
                                                 object, work, pending, nullptr, extents);
}

void testEachTriangle(CpuDepthBuffer& buffer, const RasterPass& pass,
                      std::span<const ScreenTriangle> triangles, std::uint8_t* fullyVisible,
                      RasterWork& work, std::uint32_t object, PendingBlocks* pending,
                      const TriangleExtents* extents) {
  if (extents != nullptr) checkTestSize(triangles.size());
  (void)HWY_DYNAMIC_DISPATCH(TestUntilOccluded)(buffer, pass, triangles.data(), triangles.size(),
                                                object, work, pending, fullyVisible, extents);
}

std::size_t testQuadsUntilOccluded(CpuDepthBuffer& buffer, const RasterPass& pass,
                                   std::span<const ScreenQuad> quads, RasterWork& work,
                                   std::uint32_t object, PendingBlocks* pending) {
  checkTestSize(quads.size());
  return HWY_DYNAMIC_DISPATCH(TestQuadsUntilOccluded)(buffer, pass, quads.data(), quads.size(),
                                                      object, work, pending);
}

std::size_t prepareWrites(const CpuDepthBuffer& buffer, const RasterPass& pass,
                          std::span<const ScreenTriangle> triangles,
                          PreparedWrite<ScreenTriangle>* out, const TriangleExtents* extents) {
  if (extents != nullptr) checkTestSize(triangles.size());
  return HWY_DYNAMIC_DISPATCH(PrepareTriangles)(buffer, pass, triangles.data(), triangles.size(),
                                                out, extents);
}

std::size_t prepareWrites(const CpuDepthBuffer& buffer, const RasterPass& pass,
                          std::span<const ScreenQuad> quads, PreparedWrite<ScreenQuad>* out) {
  return HWY_DYNAMIC_DISPATCH(PrepareQuads)(buffer, pass, quads.data(), quads.size(), out);
}

void writePrepared(CpuDepthBuffer& buffer, const RasterPass& pass,
                   std::span<PreparedWrite<ScreenTriangle>> writes, BlockMask mask,
                   RasterWork& work, std::uint32_t object) {
  HWY_DYNAMIC_DISPATCH(WritePreparedTriangles)
  (buffer, pass, writes.data(), writes.size(), mask, object, work);
}

void writePrepared(CpuDepthBuffer& buffer, const RasterPass& pass,
                   std::span<PreparedWrite<ScreenQuad>> writes, BlockMask mask, RasterWork& work,
                   std::uint32_t object) {
  HWY_DYNAMIC_DISPATCH(WritePreparedQuads)
  (buffer, pass, writes.data(), writes.size(), mask, object, work);
}

const char* rasteriserTarget() { return HWY_DYNAMIC_DISPATCH(TargetName)(); }

}  // namespace cdb
#endif
