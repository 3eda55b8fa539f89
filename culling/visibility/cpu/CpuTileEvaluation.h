#pragma once
// Step 2 of running a recording: one screen tile of a chain (passes sharing a depth buffer)
// evaluated on its own, on demand, walking the tile's items in issue order. A write is made
// pending in the 8x8 blocks of its rectangle (dropped where it is behind everything stored); the
// writes of one command walked with no test between them are listed in those blocks as one group. A
// test another tile found occluded is skipped (the early-out); one that no pending write can lie
// in front of, and everything stored lies behind, is decided by bounds; otherwise it is tested
// against what the tile holds and, visible there, again in the blocks with pending writes it may
// read, each drawn there first (prepared once per tile). In an order-independent pass a test of
// object i reads no pending write of i's own. The walk stops after the tile's last test still open
// (the writes after it are walked only if a later pass goes on in the buffer, before that pass'
// items). A write no undecided test reads is never drawn; the answer is that of drawing every
// write and testing every piece, since stored depth is the nearest of what was written and a
// pending write left out is behind the test wherever both have pixels.
#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "core/GrowOnlyArray.h"
#include "culling/visibility/cpu/CpuAnswers.h"
#include "culling/visibility/cpu/CpuBins.h"
#include "culling/visibility/cpu/CpuDepthBuffer.h"
#include "culling/visibility/cpu/CpuMeshBounds.h"
#include "culling/visibility/cpu/CpuRasteriser.h"
#include "scenes/SceneGeometry.h"

namespace cdb {

// How a recording is evaluated. The answers and the depths tests read are the same for every
// setting; only the work done differs (plain: demandDriven and earlyOut off, one tile).
struct CpuEvaluation {
  // Pixels, a multiple of 8, at most 64 when demand-driven (a write's blocks in a tile are a
  // 64-bit mask); 0: the whole frame is one tile.
  int tileSize = 64;
  bool demandDriven = true;  // off: every write rasterised where it is drawn, every test tested
  bool earlyOut = true;      // a test found occluded in one tile is skipped in the others
  // Groups of pending writes listed in one block, and writes pending in one tile, before those are
  // drawn (a test scans the groups listed in its blocks, and a pending write keeps its prepared
  // pieces; measured in docs/cpu-backend-history.md: a tile of env2's dragon pile gets tens of
  // thousands of cullide_bvh's node boxes, and at 4,096 half of its writes' drawing was for the
  // limit).
  std::size_t mostPendingInBlock = 1024;
  std::size_t mostPendingInTile = 16384;
};

// The attached scene, and what binning knows of its meshes.
struct CpuScene {
  const SceneGeometry& geometry;
  std::span<const CpuMeshBounds> bounds;
};

struct CpuPendingWrite {
  static constexpr std::uint32_t kNotSetUp = ~std::uint32_t{0};
  BlockMask remaining = 0;  // blocks of its rectangle in the tile it is not drawn in yet
  float kLo = 0.f, kHi = 0.f;
  std::uint32_t object = 0;
  const CpuRun* run = nullptr;
  std::uint32_t item = 0;
  // Its pieces prepared in the evaluating thread's CpuPreparedScratch (triangles or quads), once a
  // test needed some of its blocks; set up again when a later fetch goes on in the tile.
  std::uint32_t firstPrepared = kNotSetUp;
  std::uint32_t preparedCount = 0;
  bool quads = false;
  bool counted = false;  // in CpuTileWork::writesRasterised
};

// Consecutive writes of one command made pending in a tile's walk, with no test walked between
// them: the block lists hold such a group once (its blocks the union of its writes', its nearest
// key theirs), not each write; a test that can see it in a block draws those of its writes pending
// there that can lie in front of the test.
struct CpuPendingGroup {
  BlockMask blocks = 0;
  float kLo = std::numeric_limits<float>::infinity();
  std::uint32_t object = 0;
  std::uint32_t command = 0;
  bool orderIndependent = false;  // its pass'
  const CpuRun* run = nullptr;
  std::uint32_t firstWrite = 0, endWrite = 0;  // its writes in CpuTileState::pending
};

// Prepared pieces of a tile's pending writes, set up in storage that only grows and never moves
// (a tile of a dragon pile can hold a hundred thousand prepared pieces; a vector grown by copying,
// and filled when allocated, made that tens of megabytes of fresh pages, each a page fault, in the
// frames where the pile grows).
template <class Piece>
class CpuPreparedPieces {
 public:
  // Room for `count` pieces prepared next (prepareWrites writes them), by the index of the first.
  std::uint32_t room(std::size_t count) {
    const auto first = static_cast<std::uint32_t>(storage_.size());
    storage_.resizeForOverwrite(first + count);
    return first;
  }
  // Of the room at `first`, the first `count` pieces are prepared: the rest goes back.
  void add(std::uint32_t first, std::size_t count) { storage_.resizeForOverwrite(first + count); }
  [[nodiscard]] PreparedWrite<Piece>* at(std::uint32_t index) { return storage_.data() + index; }
  void clear() { storage_.clear(); }

 private:
  GrowOnlyArray<PreparedWrite<Piece>> storage_;
};

// The prepared pieces of the tile a thread evaluates: one storage per thread, reused tile after
// tile, so it stays in cache and is allocated once.
struct CpuPreparedScratch {
  CpuPreparedPieces<ScreenTriangle> triangles;
  CpuPreparedPieces<ScreenQuad> quads;
  void clear() { triangles.clear(), quads.clear(); }
};

// Per block of a tile, a list of indices in the order pushed: the first kInline of each in one
// array for all blocks (a write made pending in a dozen blocks touches a few cache lines, not a
// dozen vectors' headers and heaps), the rest in a vector per block.
class CpuBlockLists {
 public:
  static constexpr int kBlocks = 64;
  static constexpr std::size_t kInline = 32;
  void push(std::size_t b, std::uint32_t i) {
    std::uint32_t& n = count_[b];
    if (n < kInline)
      first_[b][n] = i;
    else
      more_[b].push_back(i);
    ++n;
  }
  [[nodiscard]] std::size_t size(std::size_t b) const { return count_[b]; }
  void clear(std::size_t b) {
    if (count_[b] > kInline) more_[b].clear();
    count_[b] = 0;
  }
  // Calls f(i) for each entry of block b in order, stopping when f returns true; true if one did.
  template <class F>
  bool any(std::size_t b, F&& f) const {
    const std::size_t n = count_[b];
    for (std::size_t k = 0; k < std::min(n, kInline); ++k)
      if (f(first_[b][k])) return true;
    for (std::size_t k = kInline; k < n; ++k)
      if (f(more_[b][k - kInline])) return true;
    return false;
  }
  // Calls f(i) for each entry of block b in order.
  template <class F>
  void forEach(std::size_t b, F&& f) const {
    any(b, [&](std::uint32_t i) {
      f(i);
      return false;
    });
  }
  // Keeps the entries of block b for which keep(i) is true, in order.
  template <class Keep>
  void keepIf(std::size_t b, Keep&& keep) {
    const std::size_t n = count_[b];
    std::size_t kept = 0;
    const auto visit = [&](std::uint32_t i) {
      if (!keep(i)) return;
      if (kept < kInline)
        first_[b][kept] = i;
      else
        more_[b][kept - kInline] = i;
      ++kept;
    };
    for (std::size_t k = 0; k < std::min(n, kInline); ++k) visit(first_[b][k]);
    for (std::size_t k = kInline; k < n; ++k) visit(more_[b][k - kInline]);
    count_[b] = static_cast<std::uint32_t>(kept);
    if (n > kInline) more_[b].resize(kept > kInline ? kept - kInline : 0);
  }

 private:
  std::array<std::uint32_t, kBlocks> count_{};
  std::array<std::array<std::uint32_t, kInline>, kBlocks> first_;
  std::array<std::vector<std::uint32_t>, kBlocks> more_;
};

// In an order-independent pass, what a block's list needs besides the nearest key of its pending
// writes to say without a scan whether one of another object than a test's can lie in front of it:
// the object of a write with that key, and the nearest key of the other objects' writes.
struct CpuPendingOthers {
  std::uint32_t object = 0;
  float nearest = std::numeric_limits<float>::infinity();
  // Writes of `o` with nearest key `k` join a list whose nearest key was `key`.
  void add(float key, float k, std::uint32_t o) {
    if (o == object) return;
    if (k < key) {  // (`key` is the nearest of all, and its object is not o)
      nearest = key, object = o;
    } else {
      nearest = std::min(nearest, k);
    }
  }
};

// A tile of a chain's depth buffer: the depths resolved so far and the writes still pending.
struct CpuTileState {
  static constexpr int kBlocks = CpuBlockLists::kBlocks;  // at most, in a demand-driven tile
  CpuDepthBuffer depth;
  // Writes not drawn everywhere yet, in issue order (an entry stays until nothing is pending), in
  // groups (CpuPendingGroup; the last one still open while `groupOpen`: in no block's list yet),
  // and per block of the tile the groups with writes not drawn there yet (indices into `groups`,
  // ascending) with a key no farther than the nearest of those writes (+infinity: none), and in an
  // order-independent pass one for the other objects' (kept for every write there: such a pass
  // clears, so a chain's passes are all order-independent or none are).
  std::vector<CpuPendingWrite> pending;
  std::vector<CpuPendingGroup> groups;
  bool groupOpen = false;
  CpuBlockLists pendingIn;
  std::array<float, kBlocks> pendingNearest = [] {
    std::array<float, kBlocks> none;
    none.fill(std::numeric_limits<float>::infinity());
    return none;
  }();
  std::array<CpuPendingOthers, kBlocks> pendingOthers{};
  BlockMask pendingBlocks = 0;  // blocks in whose lists a group is
  float sign = 0.f;             // the key order of the pass of its last item (0: none yet)
  std::uint64_t chain = 0;      // which chain's tile it holds (0: none)
  // Where the walk of a run's last chain stopped, after the tile's last test still open: the
  // writes from `from` on were not made pending, and are, before anything of a later pass that
  // goes on in the buffer (evaluateTile). run == nullptr: none left.
  struct Rest {
    const CpuRun* run = nullptr;
    std::uint32_t chain = 0;
    std::uint32_t from = 0;
  } rest;
};

// What tiles did, summed into VisibilityCounters.
struct CpuTileWork {
  RasterWork raster;
  std::uint64_t tests = 0;          // (test item, tile) visits
  std::uint64_t testsByBounds = 0;  // of them decided without rasterising a pixel
  std::uint64_t testsSkipped = 0;   // of them skipped: answered elsewhere
  std::uint64_t writes = 0;         // (write item, tile) visits
  std::uint64_t writesRasterised = 0;
  CpuTileWork& operator+=(const CpuTileWork& o);
};

// Makes `state` tile `tile` of a fresh buffer of the chain `chainId` (every pixel at
// `clearValue`, nothing pending).
void startTile(CpuTileState& state, const CpuChain& chain, std::uint32_t tile, float clearValue,
               std::uint64_t chainId);

// Walks the items chain `chain` of `run` binned to tile `tile`, on `state` (that tile of the
// chain's buffer), preparing pieces into `prepared` (emptied again at the end).
void evaluateTile(CpuTileState& state, const CpuScene& scene, const CpuRun& run,
                  std::uint32_t chain, std::uint32_t tile, const CpuEvaluation& evaluation,
                  CpuAnswers answers, CpuPreparedScratch& prepared, CpuTileWork& work);

// Rasterises every write of `items` (of `run`) into `state`, in order: the plain evaluation of
// what a tile stores.
void rasteriseWrites(CpuTileState& state, const CpuScene& scene, const CpuRun& run,
                     std::span<const std::uint32_t> items, CpuTileWork& work);

}  // namespace cdb
