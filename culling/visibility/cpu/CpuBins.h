#pragma once
// Step 1 of running a recording: binning. Each command is cut into items (a chunk of
// kChunkTriangles triangles, or one box), each item gets the pixel rectangle and the key range
// its pixels can have (from a box in its object's frame, so no triangle is transformed), and the
// items of each chain of passes sharing one depth buffer are listed per screen tile, in issue
// order (a chain whose tests are gated by an earlier chain's, once that one ran). A tile's list
// is all CpuTileEvaluation needs to evaluate that tile on its own.
#include <tbb/task_arena.h>

#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "core/GrowOnlyArray.h"
#include "culling/visibility/cpu/CpuMeshBounds.h"
#include "culling/visibility/cpu/CpuPixelRect.h"
#include "culling/visibility/cpu/CpuRecording.h"
#include "culling/visibility/cpu/CpuVertexSets.h"

namespace cdb {

// In 32 bytes: a tile reads the items binned to it from all over the recording's, each once per
// tile it reaches (a million node boxes a frame in `cullide_bvh`), so an item is half a cache line.
// Its object and pass are its command's (CpuCommand::object, CpuBins::passOf).
struct CpuItem {
  static constexpr std::uint32_t kMostCommands = std::uint32_t{1} << 22;  // in a recording
  std::uint32_t command : 22 = 0;
  std::uint32_t count : 7 = 0;  // triangles (at most kChunkTriangles), or 1 box
  std::uint32_t test : 1 = 0;
  std::uint32_t answerEach : 1 = 0;  // a test answering per triangle (answer + i for its i-th)
  std::uint32_t box : 1 = 0;         // one box (else a chunk of triangles)
  // Range: its first mesh triangle; Listed: its first entry of CpuRecording::listed; Boxes: its
  // box in CpuRecording::boxes.
  std::uint32_t first = 0;
  QueryIndex answer = 0;  // a test's (first) answer
  // Chunks: its entry of CpuBins::parts.
  std::uint32_t parts = 0;
  // Every pixel any of its pieces covers lies in `rect` (empty: none in the frame), and every key
  // it tests or writes there (its offsets toward "occluded" included) in [kLo, kHi].
  PixelRect rect;
  float kLo = 0.f;
  float kHi = 0.f;
};
static_assert(sizeof(CpuItem) == 32);
static_assert(kChunkTriangles < (1u << 7), "an item's count is 7 bits");

// A chunk item's rectangle per part of kPartTriangles triangles, in order.
using CpuItemParts = std::array<PixelRect, kChunkTriangles / kPartTriangles>;

// Passes that share one depth buffer, in order: a pass that clears starts one; a SharedSecond
// pass, or draws going on after a fetch, join the one before (or the buffer a previous recording
// left: its first pass CpuPass::continues).
struct CpuChain {
  std::uint32_t firstPass = 0, endPass = 0;
  int resolution = 0;
  int tileSize = 0;               // pixels, a multiple of CpuDepthBuffer::kBlock
  int tilesX = 0;                 // tiles per row and per column
  bool orderIndependent = false;  // its buffer keeps the others' planes (CpuDepthBuffer)
  float clearValue = 1.f;         // the value its first pass clears to (unless it continues)
  // Items of tile t: binned[offsets[t] .. offsets[t + 1]), ascending (issue order).
  std::vector<std::uint32_t> offsets;
  GrowOnlyArray<std::uint32_t> binned;
  std::vector<std::uint32_t> tilesUsed;  // tiles with at least one item, ascending
  std::vector<std::uint32_t> fill;       // binning's scratch: per run of items, per tile
  // Binning's scratch: the tile column (row) of each pixel column (row), for tileOfFor's
  // resolution and tile size.
  std::vector<std::uint16_t> tileOf;
  std::pair<int, int> tileOfFor{0, 0};
  [[nodiscard]] std::span<const std::uint32_t> itemsOf(std::uint32_t tile) const {
    return {binned.data() + offsets[tile], binned.data() + offsets[tile + 1]};
  }
};

struct CpuBins {
  GrowOnlyArray<CpuItem> items;
  // Per CpuRecording::boxes, under the matrix of the commands that draw it: the unit cube's
  // matrix into screen space, which binning bounds the box's items from and a tile sets its faces
  // up from.
  GrowOnlyArray<ScreenMatrix> boxCubes;
  GrowOnlyArray<CpuItemParts> parts;     // of the chunk items (CpuItem::parts)
  std::vector<std::uint32_t> firstItem;  // per command, and one past the last
  std::vector<CpuChain> chains;          // the first chainCount are this recording's
  std::size_t chainCount = 0;
  std::vector<std::uint32_t> passOf;      // each command's pass
  std::vector<std::uint32_t> firstParts;  // binning's scratch: each command's first parts entry
  // Binning's scratch: runs of items bounded as one task (command, first and end item in it).
  std::vector<std::array<std::uint32_t, 3>> itemTasks;
};

// A recording with its bins: what one fetch ran, kept while writes it left pending may still be
// resolved (its buffer goes on in a later recording).
struct CpuRun {
  CpuRecording recording;
  CpuBins bins;
  CpuVertexSets vertexSets;
};

// Tiles of a frame (per row and column) at `tileSize` pixels.
[[nodiscard]] inline int tilesAcross(int resolution, int tileSize) {
  return (resolution + tileSize - 1) / tileSize;
}

// Makes the (closed) recording's items and chains, their tiles' lists not yet (binChains); its
// commands' meshes are the scene's, `bounds` their CpuMeshBounds, `vertexSets` its vertex sets
// (assigned: their part bounds are made here). Tiles are `tileSize` pixels (0: one tile the whole
// frame, rounded up to a block); a chain that continues a buffer keeps that buffer's
// `continuedTileSize`. Runs on `arena` when given.
void binRecording(const CpuRecording& recording, std::span<const CpuMeshBounds> bounds,
                  const CpuVertexSets& vertexSets, int tileSize, int continuedTileSize,
                  tbb::task_arena* arena, CpuBins& bins);

class CpuAnswers;

// Lists the items of chains [first, end) per tile. With `answers` (the fetch's answers so far), a
// test none of whose answers is open any more (each found occluded, or its gate's:
// CpuCommand::gateBack) is left out, as evaluating it could change nothing (a chain binned after
// the chains holding its tests' gates ran). Returns the (item, tile) entries left out.
std::uint64_t binChains(const CpuRecording& recording, CpuBins& bins, std::size_t first,
                        std::size_t end, tbb::task_arena* arena, const CpuAnswers* answers);

}  // namespace cdb
