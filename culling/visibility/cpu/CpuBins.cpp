#include "culling/visibility/cpu/CpuBins.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>

#include "core/ArenaForEach.h"
#include "culling/visibility/cpu/CpuAnswers.h"
#include "culling/visibility/cpu/CpuDepthBuffer.h"
#include "culling/visibility/cpu/CpuPieces.h"

namespace cdb {

namespace {

// Items of command `c`: its triangles in chunks of kChunkTriangles (a Range's on the mesh's chunk
// grid, as it starts at 0), or its boxes one by one.
std::uint32_t itemCount(const CpuCommand& c) {
  return c.source == CpuCommand::Source::Boxes ? c.count
                                               : (c.count + kChunkTriangles - 1) / kChunkTriangles;
}

// Screen extent of a box (centre and half extents) in the frame of `toScreen`: exact up to
// rounding. (Plain arithmetic on three coordinates: binning bounds every part of every chunk.)
struct ScreenExtent {
  double lo[3], hi[3];
  [[nodiscard]] bool finite() const {
    // (Finite values minus themselves are 0; infinities and NaN give NaN.)
    double sum = 0.0;
    for (int i = 0; i < 3; ++i) sum += (lo[i] - lo[i]) + (hi[i] - hi[i]);
    return sum == 0.0;
  }
};
ScreenExtent extentOf(const ScreenMatrix& m, const double (&centre)[3], const double (&half)[3]) {
  ScreenExtent e;
  for (int i = 0; i < 3; ++i) {
    const double mid = m(i, 0) * centre[0] + m(i, 1) * centre[1] + m(i, 2) * centre[2] + m(i, 3);
    const double reach = std::abs(m(i, 0)) * half[0] + std::abs(m(i, 1)) * half[1] +
                         std::abs(m(i, 2)) * half[2];
    e.lo[i] = mid - reach, e.hi[i] = mid + reach;
  }
  return e;
}
ScreenExtent extentOf(const ScreenMatrix& m, const Eigen::AlignedBox3f& box) {
  double centre[3], half[3];
  for (int i = 0; i < 3; ++i) {
    const double lo = box.min()[i], hi = box.max()[i];
    centre[i] = (lo + hi) * 0.5, half[i] = (hi - lo) * 0.5;
  }
  return extentOf(m, centre, half);
}

// The pixels a triangle within the extent can cover: a pixel more on each side than the set-up
// can reach (its margin, the conservative rule's extra pixel), so that every triangle's pixel box
// (setupBounds) lies inside. Empty when off-screen; the whole frame when not finite (the set-up
// draws no such triangle).
PixelRect pixelsOf(const ScreenExtent& e, bool finite, const RasterPass& pass) {
  const int last = pass.resolution - 1;
  if (!finite) return {0, 0, last, last};
  const double m = pass.marginPx + 1.0;
  // floor and ceil of values clamped to [-2, last + 2] first, by an integer conversion (the
  // build's baseline instruction set has no rounding instruction: std::floor is a call). Both are
  // monotone and the clamp's ends integers, so every rectangle, and every empty one, is the same
  // as unclamped.
  const double lowEnd = -2.0, highEnd = last + 2.0;
  const auto floorOf = [&](double v) {
    v = std::clamp(v, lowEnd, highEnd);
    const auto t = static_cast<int>(v);  // toward zero
    return t - (v < t ? 1 : 0);
  };
  const auto ceilOf = [&](double v) {
    v = std::clamp(v, lowEnd, highEnd);
    const auto t = static_cast<int>(v);
    return t + (v > t ? 1 : 0);
  };
  const int x0 = std::max(0, floorOf(e.lo[0] - m) - 1);
  const int y0 = std::max(0, floorOf(e.lo[1] - m) - 1);
  const int x1 = std::min(last, ceilOf(e.hi[0] + m));
  const int y1 = std::min(last, ceilOf(e.hi[1] + m));
  if (x1 < x0 || y1 < y0) return {};
  return {x0, y0, x1, y1};
}

// An item's rectangle (`rect` when given: that of an item with the same extent in a pass of the
// same pixel grid) and key range: keys widened far beyond the rounding of the transforms, and
// moved by the pass' offsets as the set-up moves them.
void boundItem(const ScreenExtent& e, bool finite, const RasterPass& pass, CpuItem& item,
               const PixelRect* rect = nullptr) {
  item.rect = rect != nullptr ? *rect : pixelsOf(e, finite, pass);
  if (!finite) {
    item.kLo = pass.keyLo, item.kHi = pass.keyHi;
    return;
  }
  const double slack = 1e-9 * (1.0 + std::abs(e.lo[2]) + std::abs(e.hi[2]));
  const double shift = pass.conservative ? (item.test ? pass.depthEpsilon : -pass.depthEpsilon)
                                         : (item.test ? pass.rawTestOffset : 0.0);
  const auto clampToPass = [&](float v) { return std::clamp(v, pass.keyLo, pass.keyHi); };
  item.kLo = clampToPass(raster_detail::roundDown(e.lo[2] + shift - slack));
  item.kHi = clampToPass(raster_detail::roundUp(e.hi[2] + shift + slack));
}

// A mesh part's (or a listed part's) screen bounds from its box, written into `b` field by field.
// (Returned by value, they were put together on the stack with 8- and 2-byte stores and copied
// out 16 bytes at a time: each such load waits for the stores it spans.)
void partBoundsOf(const ScreenMatrix& toScreen, const Eigen::AlignedBox3f& box,
                  const RasterPass& pass, CpuPartScreenBounds& b) {
  if (box.isEmpty()) {
    b.rect = {}, b.present = false, b.finite = false;
    return;
  }
  const ScreenExtent e = extentOf(toScreen, box);
  for (int i = 0; i < 3; ++i) b.lo[i] = e.lo[i], b.hi[i] = e.hi[i];
  b.present = true;
  b.finite = e.finite();
  b.rect = pixelsOf(e, b.finite, pass);
}

// A chunk item's bounds from its parts' (null or not present: parts it does not have): each
// part's rectangle, and the item's from the union of their extents (every triangle lies in its
// part's box, so in its part's extent; tighter than the extent of the parts' union box).
void boundChunk(std::span<const CpuPartScreenBounds* const> parts, const RasterPass& pass,
                CpuItem& item, CpuItemParts& rects) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  ScreenExtent all{{kInf, kInf, kInf}, {-kInf, -kInf, -kInf}};
  bool any = false, finite = true;
  for (std::size_t p = 0; p < rects.size(); ++p) {
    const CpuPartScreenBounds* part = parts[p];
    if (part == nullptr || !part->present) {
      rects[p] = {};
      continue;
    }
    rects[p] = part->rect;
    for (int i = 0; i < 3; ++i)
      all.lo[i] = std::min(all.lo[i], part->lo[i]), all.hi[i] = std::max(all.hi[i], part->hi[i]);
    finite = finite && part->finite;
    any = true;
  }
  if (!any) {
    item.rect = {}, item.kLo = item.kHi = 0.f;
    return;
  }
  boundItem(all, finite, pass, item);
}

// Whether passes `a` and `b` give an item of the same extent the same rectangle and key range.
bool boundsAlike(const RasterPass& a, const RasterPass& b) {
  return a.resolution == b.resolution && a.marginPx == b.marginPx && a.keyLo == b.keyLo &&
         a.keyHi == b.keyHi && a.depthEpsilon == b.depthEpsilon &&
         a.rawTestOffset == b.rawTestOffset && a.conservative == b.conservative;
}

// Items [n0, n1) of command `ci`, at items[n0 ..]; a chunk item's parts at
// bins.parts[firstParts + n0 ..]. A part that is a whole part of the mesh takes its vertex set's
// bounds of that part (made once for every command of the set).
void makeItems(const CpuRecording& recording, std::span<const CpuMeshBounds> bounds,
               const CpuVertexSets& vertexSets, std::uint32_t ci, std::uint32_t pass,
               CpuItem* items, CpuBins& bins, std::uint32_t firstParts, std::uint32_t n0,
               std::uint32_t n1) {
  const CpuCommand& c = recording.commands[ci];
  const RasterPass& raster = recording.passes[pass].raster;
  CpuItem base;
  base.command = ci, base.answer = c.query;
  base.test = c.role == CpuCommand::Role::Test;
  base.answerEach = base.test && c.answerEach;
  const auto answerOf = [&](std::uint32_t offset) { return c.query + (c.answerEach ? offset : 0); };
  // Item n with the fields the command's items share: the first from `base`, the others copied
  // from the first, in memory. (Copied from `base`, a local, GCC composed each item on the stack in
  // parts and read it back whole: a store-forwarding stall per item, 40% of the box loop's own
  // time.)
  const auto itemAt = [&](std::uint32_t n) -> CpuItem& {
    CpuItem& item = items[n];
    item = n == n0 ? base : items[n0];
    return item;
  };
  if (c.itemsOf != CpuCommand::kNone) {
    // The items of an earlier command of the same role, list and matrix (binning runs those
    // first), when its pass bounds them alike: the same rectangles and key ranges.
    const RasterPass& owner = recording.passes[bins.passOf[c.itemsOf]].raster;
    if (boundsAlike(owner, raster)) {
      const CpuItem* from = bins.items.data() + bins.firstItem[c.itemsOf];
      for (std::uint32_t n = n0; n < n1; ++n) {
        CpuItem& item = items[n] = from[n];
        item.command = ci;
        item.answer = answerOf(c.source == CpuCommand::Source::Boxes ? n : n * kChunkTriangles);
        item.answerEach = base.answerEach;
      }
      return;
    }
  }
  if (c.source == CpuCommand::Source::Boxes) {
    // A command that recorded its boxes puts them in screen space; one sharing them finds them
    // there (binning runs those after the others), and their rectangles too when its pass has the
    // same pixel grid.
    const CpuItem* ownerItems = nullptr;
    if (c.sharesBoxes()) {
      const RasterPass& owner = recording.passes[bins.passOf[c.boxesOf]].raster;
      if (owner.resolution == raster.resolution && owner.marginPx == raster.marginPx)
        ownerItems = bins.items.data() + bins.firstItem[c.boxesOf];
    }
    base.count = 1, base.box = true;
    for (std::uint32_t b = n0; b < n1; ++b) {
      CpuItem& item = itemAt(b);
      item.first = c.first + b, item.answer = answerOf(b);
      ScreenMatrix& cube = bins.boxCubes[item.first];
      // (Made in place: assigned, it was made on the stack and copied 16 bytes at a time across
      // the function's 8- and 16-byte stores, each such load waiting for them.)
      if (!c.sharesBoxes())
        ::new (&cube) ScreenMatrix(cubeToScreen(c.toScreen, recording.boxes[item.first]));
      const ScreenExtent e = extentOf(cube, {0.0, 0.0, 0.0}, {1.0, 1.0, 1.0});
      boundItem(e, e.finite(), raster, item, ownerItems ? &ownerItems[b].rect : nullptr);
    }
    return;
  }
  const CpuMeshBounds& mesh = bounds[c.mesh];
  constexpr std::size_t kParts = kChunkTriangles / kPartTriangles;
  static_assert(kParts == CpuVertexSets::kChunkParts);
  // (Parts of one item lie in at most kParts mesh chunks: each its own copy when another thread
  // is making that chunk's.)
  std::array<std::array<CpuPartScreenBounds, kParts>, kParts> own;
  const auto meshPart = [&](std::uint32_t q, std::uint32_t p) {
    const CpuPartScreenBounds* chunkParts = vertexSets.parts(
        c, q / kParts, mesh.parts.size(),
        [&](std::size_t first, std::size_t count, CpuPartScreenBounds* out) {
          for (std::size_t k = 0; k < count; ++k)
            partBoundsOf(c.toScreen, mesh.parts[first + k], raster, out[k]);
        },
        own[p]);
    return chunkParts + q % kParts;
  };
  std::array<const CpuPartScreenBounds*, kParts> parts;
  std::array<CpuPartScreenBounds, kParts> listedParts;
  for (std::uint32_t n = n0, at = n0 * kChunkTriangles; n < n1; ++n, at += kChunkTriangles) {
    CpuItem& item = itemAt(n);
    item.first = c.first + at;
    const std::uint32_t count = std::min(kChunkTriangles, c.count - at);
    item.count = count;
    item.answer = answerOf(at);
    item.parts = firstParts + n;
    // Part p: the item's triangles [p, p + 1) * kPartTriangles (as chunkPieces reads them); a
    // Range's are the mesh's own parts.
    for (std::uint32_t p = 0; p < kParts; ++p) {
      const std::uint32_t p0 = p * kPartTriangles;
      const std::uint32_t p1 = std::min(count, p0 + kPartTriangles);
      parts[p] = nullptr;
      if (p0 >= p1) continue;
      if (c.source == CpuCommand::Source::Range) {
        parts[p] = meshPart((item.first + p0) / kPartTriangles, p);
        continue;
      }
      // (Positions ascending: a full part listing one part of the mesh is that part, whose
      // bounds its vertex set has; the whole-mesh lists of CULLIDE's triangle level are all such.)
      const std::uint32_t* listed = recording.listed.data() + item.first;
      if (p1 - p0 == kPartTriangles &&
          listed[p0] / kPartTriangles == listed[p1 - 1] / kPartTriangles) {
        parts[p] = meshPart(listed[p0] / kPartTriangles, p);
        continue;
      }
      Eigen::AlignedBox3f box;
      for (std::uint32_t i = p0; i < p1; ++i) box.extend(mesh.triangles[listed[i]]);
      partBoundsOf(c.toScreen, box, raster, listedParts[p]);
      parts[p] = &listedParts[p];
    }
    boundChunk(parts, raster, item, bins.parts[item.parts]);
  }
}

constexpr std::uint32_t kItemsPerTask = 512;

// A chain's items listed per tile, in issue order: each run of items counts its
// (item, tile) entries per tile, the runs' counts in order give where each run writes in a tile's
// list, and each run writes its own. With `answers`, tests none of whose answers is open are left
// out; the entries they would have had are counted in `leftOut`.
void binChain(const CpuRecording& recording, const CpuBins& bins, tbb::task_arena* arena,
              const CpuAnswers* answers, CpuChain& chain, std::uint64_t& leftOut) {
  const std::uint32_t firstCommand = recording.passes[chain.firstPass].firstCommand;
  const std::uint32_t endCommand = recording.passes[chain.endPass - 1].endCommand;
  const std::uint32_t firstItem = bins.firstItem[firstCommand];
  const std::uint32_t endItem = bins.firstItem[endCommand];
  const std::size_t tiles = static_cast<std::size_t>(chain.tilesX) * chain.tilesX;
  chain.offsets.resize(tiles + 1);  // every entry written below
  // (A table, not a division per item and coordinate.)
  if (chain.tileOfFor != std::pair{chain.resolution, chain.tileSize}) {
    chain.tileOf.resize(static_cast<std::size_t>(chain.resolution));
    for (int x = 0; x < chain.resolution; ++x)
      chain.tileOf[static_cast<std::size_t>(x)] = static_cast<std::uint16_t>(x / chain.tileSize);
    chain.tileOfFor = {chain.resolution, chain.tileSize};
  }
  const std::uint16_t* tileOf = chain.tileOf.data();
  const auto forTiles = [&](const CpuItem& item, auto&& visit) {
    const int tx0 = tileOf[item.rect.x0], tx1 = tileOf[item.rect.x1];
    for (int ty = tileOf[item.rect.y0]; ty <= tileOf[item.rect.y1]; ++ty)
      for (int tx = tx0; tx <= tx1; ++tx) visit(static_cast<std::size_t>(ty) * chain.tilesX + tx);
  };
  // One run without threads; with them at most four a thread (the runs' counts are summed tile by
  // tile), of at least kItemsPerTask items.
  const std::uint32_t items = endItem - firstItem;
  const std::uint32_t most = arena ? 4 * static_cast<std::uint32_t>(arena->max_concurrency()) : 1;
  const std::uint32_t perRun = std::max(kItemsPerTask, (items + most - 1) / most);
  const std::size_t runs = (items + perRun - 1) / perRun;
  const auto eachItem = [&](std::size_t run, auto&& visit) {
    const std::uint32_t i0 = firstItem + static_cast<std::uint32_t>(run) * perRun;
    const std::uint32_t i1 = std::min(endItem, i0 + perRun);
    std::uint32_t* at = chain.fill.data() + run * tiles;
    std::uint64_t out = 0;
    for (std::uint32_t i = i0; i < i1; ++i) {
      const CpuItem& item = bins.items[i];
      if (item.rect.empty()) continue;
      if (answers != nullptr && item.test &&
          answered(item, *answers, recording.commands[item.command].gateBack)) {
        forTiles(item, [&](std::size_t) { ++out; });
        continue;
      }
      forTiles(item, [&](std::size_t t) { visit(i, at[t]); });
    }
    return out;
  };
  chain.fill.assign(runs * tiles, 0);
  std::vector<std::uint64_t> outOfRun(runs, 0);
  forEachIndex(arena, runs, [&](std::size_t r) {
    outOfRun[r] = eachItem(r, [](std::uint32_t, std::uint32_t& n) { ++n; });
  });
  for (const std::uint64_t n : outOfRun) leftOut += n;
  chain.tilesUsed.clear();
  std::uint32_t entries = 0;
  for (std::size_t t = 0; t < tiles; ++t) {
    chain.offsets[t] = entries;
    for (std::size_t r = 0; r < runs; ++r) {
      std::uint32_t& n = chain.fill[r * tiles + t];  // the run's count in the tile, then its start
      const std::uint32_t count = n;
      n = entries;
      entries += count;
    }
    if (entries > chain.offsets[t]) chain.tilesUsed.push_back(static_cast<std::uint32_t>(t));
  }
  chain.offsets[tiles] = entries;
  chain.binned.resize(entries);
  forEachIndex(arena, runs, [&](std::size_t r) {
    eachItem(r, [&](std::uint32_t i, std::uint32_t& n) { chain.binned[n++] = i; });
  });
}

}  // namespace

void binRecording(const CpuRecording& recording, std::span<const CpuMeshBounds> bounds,
                  const CpuVertexSets& vertexSets, int tileSize, int continuedTileSize,
                  tbb::task_arena* arena, CpuBins& bins) {
  const std::size_t commands = recording.commands.size();
  bins.firstItem.resize(commands + 1);
  bins.firstParts.resize(commands);
  std::uint32_t total = 0, totalParts = 0;
  for (std::size_t i = 0; i < commands; ++i) {
    bins.firstItem[i] = total;
    bins.firstParts[i] = totalParts;
    const std::uint32_t n = itemCount(recording.commands[i]);
    total += n;
    if (recording.commands[i].source != CpuCommand::Source::Boxes) totalParts += n;
  }
  bins.firstItem[commands] = total;
  bins.items.resize(total);
  bins.parts.resize(totalParts);

  // Chains, and each command's pass. The chains' lists are kept from one recording to the next:
  // allocated anew, lists of this size come from fresh pages every time.
  std::size_t chains = 0;
  std::vector<std::uint32_t>& passOf = bins.passOf;
  passOf.resize(commands);
  for (std::uint32_t p = 0; p < recording.passes.size(); ++p) {
    const CpuPass& pass = recording.passes[p];
    for (std::uint32_t i = pass.firstCommand; i < pass.endCommand; ++i) passOf[i] = p;
    if (p == 0 || pass.clears) {
      if (bins.chains.size() == chains) bins.chains.emplace_back();
      CpuChain& chain = bins.chains[chains++];
      chain.firstPass = p;
      chain.resolution = pass.raster.resolution;
      constexpr int kBlock = CpuDepthBuffer::kBlock;
      chain.tileSize = pass.continues ? continuedTileSize
                       : tileSize > 0 ? tileSize
                                      : (chain.resolution + kBlock - 1) / kBlock * kBlock;
      chain.tilesX = tilesAcross(chain.resolution, chain.tileSize);
      chain.orderIndependent = pass.raster.orderIndependent;
      chain.clearValue = pass.clearValue;
    }
    bins.chains[chains - 1].endPass = p + 1;
  }
  bins.chainCount = chains;

  // Items in runs of at most kItemsPerTask, so that a command of thousands of boxes is bounded on
  // every thread.
  bins.itemTasks.clear();
  for (std::uint32_t i = 0; i < commands; ++i) {
    const std::uint32_t n = bins.firstItem[i + 1] - bins.firstItem[i];
    for (std::uint32_t n0 = 0; n0 < n; n0 += kItemsPerTask)
      bins.itemTasks.push_back({i, n0, std::min(n, n0 + kItemsPerTask)});
  }
  // In three rounds: the commands that recorded their boxes or triangles; those sharing boxes
  // (their screen form, and their rectangles, are the recording command's); those copying items
  // (of a command of one of the rounds before).
  const auto stage = [&](const auto& task) {
    const CpuCommand& c = recording.commands[task[0]];
    return c.itemsOf != CpuCommand::kNone ? 2 : c.sharesBoxes() ? 1 : 0;
  };
  const auto begin = bins.itemTasks.begin();
  const auto recorded = std::stable_partition(
      begin, bins.itemTasks.end(), [&](const auto& task) { return stage(task) == 0; });
  const auto sharing = std::stable_partition(recorded, bins.itemTasks.end(),
                                             [&](const auto& task) { return stage(task) == 1; });
  bins.boxCubes.resize(recording.boxes.size());
  const auto makeTask = [&](std::size_t t) {
    const auto [i, n0, n1] = bins.itemTasks[t];
    makeItems(recording, bounds, vertexSets, i, passOf[i], bins.items.data() + bins.firstItem[i],
              bins, bins.firstParts[i], n0, n1);
  };
  const std::size_t ends[] = {static_cast<std::size_t>(recorded - begin),
                              static_cast<std::size_t>(sharing - begin), bins.itemTasks.size()};
  std::size_t first = 0;
  for (const std::size_t end : ends) {
    forEachIndex(arena, end - first, [&](std::size_t t) { makeTask(first + t); });
    first = end;
  }
}

std::uint64_t binChains(const CpuRecording& recording, CpuBins& bins, std::size_t first,
                        std::size_t end, tbb::task_arena* arena, const CpuAnswers* answers) {
  std::vector<std::uint64_t> leftOut(end - first, 0);
  forEachIndex(arena, end - first, [&](std::size_t c) {
    binChain(recording, bins, arena, answers, bins.chains[first + c], leftOut[c]);
  });
  std::uint64_t total = 0;
  for (const std::uint64_t n : leftOut) total += n;
  return total;
}

}  // namespace cdb
