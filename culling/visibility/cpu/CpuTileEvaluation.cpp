#include "culling/visibility/cpu/CpuTileEvaluation.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <optional>
#include <type_traits>
#include <utility>

#include "culling/visibility/cpu/CpuPieces.h"

namespace cdb {

namespace {

constexpr int kBlock = CpuDepthBuffer::kBlock;

PixelRect tileRect(const CpuDepthBuffer& depth) {
  return {depth.pixelX0(), depth.pixelY0(), depth.pixelX1(), depth.pixelY1()};
}

// The blocks of the window under `rect` (inside the window) as a mask: one run of bits a row.
BlockMask blocksUnder(const CpuDepthBuffer& depth, const PixelRect& rect) {
  if (rect.x0 > rect.x1 || rect.y0 > rect.y1) return 0;
  const int x0 = CpuDepthBuffer::blockOf(rect.x0) - depth.blockX0();
  const int x1 = CpuDepthBuffer::blockOf(rect.x1) - depth.blockX0();
  const BlockMask row = ((BlockMask{2} << (x1 - x0)) - 1) << x0;
  BlockMask mask = 0;
  for (int by = CpuDepthBuffer::blockOf(rect.y0); by <= CpuDepthBuffer::blockOf(rect.y1); ++by)
    mask |= row << depth.blockIndex(depth.blockX0(), by);
  return mask;
}

// Whether every block of `mask` decides an item by its stored keys alone (in the pass' key
// order): a test whose farthest key is `key` sees nothing nearer (all stored keys behind it), a
// write whose nearest key is `key` changes nothing (all at or in front of it).
template <bool kIsTest>
bool storedDecides(const CpuDepthBuffer& depth, BlockMask mask, float sign, float key) {
  for (BlockMask m = mask; m != 0; m &= m - 1) {
    const auto i = static_cast<std::size_t>(std::countr_zero(m));
    const CpuDepthBuffer::BlockKeys stored = depth.blockKeys(i, sign);
    if (!(kIsTest ? key < stored.nearest : key >= stored.farthest)) return false;
  }
  return true;
}

// Whether a box test is occluded at the pixel under the box's centre, read from that pixel alone.
// A line of sight through a box's centre leaves the box through a face turned away from the
// viewer (or seen edge-on): one of the faces a test draws (boxPieces). In a conservative pass that
// pixel is therefore covered, at a key of at least the item's kLo; where the key stored there lies
// at or in front of kLo the test is occluded, whatever else it covers and whatever writes are
// still pending there (they only bring stored keys nearer). Not in raw passes (a pixel is covered
// by its centre there) nor in order-independent ones (whose tests read the others' plane).
bool occludedAtCentre(const CpuDepthBuffer& depth, const ScreenMatrix& cube,
                      const RasterPass& raster, float kLo, const PixelRect& inTile) {
  if (!raster.conservative || raster.orderIndependent) return false;
  const double x = std::floor(cube(0, 3)), y = std::floor(cube(1, 3));
  // (Also false for a centre that is not finite.)
  if (!(x >= inTile.x0 && x <= inTile.x1 && y >= inTile.y0 && y <= inTile.y1)) return false;
  const int px = static_cast<int>(x), py = static_cast<int>(y);
  const std::size_t index =
      depth.blockIndex(CpuDepthBuffer::blockOf(px), CpuDepthBuffer::blockOf(py));
  // (Nothing stored in the block at or in front of kLo: its pixels are not read.)
  if (kLo < depth.blockKeys(index, raster.sign).nearest) return false;
  return kLo >= depth.at(px, py) * raster.sign;
}

// What an item's command says of it: its pass' rasterisation, its object.
const RasterPass& rasterOf(const CpuRun& run, const CpuItem& item) {
  return run.recording.passes[run.bins.passOf[item.command]].raster;
}
std::uint32_t objectOf(const CpuRun& run, const CpuItem& item) {
  return run.recording.commands[item.command].object;
}
// How far back the answer gating a test item's answers lies (CpuAnswers::open; 0: not gated).
QueryIndex gateBackOf(const CpuRun& run, const CpuItem& item) {
  return run.recording.commands[item.command].gateBack;
}

// The pieces of an item that reach the buffer's window, in its pass' screen space. Set up from
// their extents (the demand-driven evaluation's tests and prepared writes) a conservative pass'
// small triangles need no corners; drawn whole (`everyCorner`: the plain evaluation) or in raw
// mode every triangle does.
void piecesOf(const CpuScene& scene, const CpuRun& run, const CpuItem& item,
              const CpuDepthBuffer& depth, CpuPieces& pieces, bool everyCorner = false) {
  const CpuRecording& recording = run.recording;
  const CpuCommand& c = recording.commands[item.command];
  const RasterPass& raster = rasterOf(run, item);
  if (c.source == CpuCommand::Source::Boxes)
    boxPieces(run.bins.boxCubes[item.first], c.role, raster.conservative, pieces);
  else
    chunkPieces(run, scene.bounds[c.mesh], c, item, tileRect(depth), raster.marginPx,
                everyCorner || !raster.conservative, pieces);
}

// A write drawn whole where it is (the plain evaluation).
void writeItem(CpuDepthBuffer& depth, const CpuScene& scene, const CpuRun& run, const CpuItem& item,
               CpuTileWork& work) {
  CpuPieces pieces;
  piecesOf(scene, run, item, depth, pieces, true);
  const RasterPass& raster = rasterOf(run, item);
  const std::uint32_t object = objectOf(run, item);
  if (pieces.areQuads)
    writePieces<ScreenQuad>(depth, raster, {pieces.quads.data(), pieces.count}, work.raster,
                            object);
  else
    writePieces<ScreenTriangle>(depth, raster, {pieces.triangles.data(), pieces.count}, work.raster,
                                object);
  ++work.writesRasterised;
}

// A pending write drawn into the blocks of `blocks` (of those it has not been drawn in), prepared
// first if no test needed it before.
template <class Piece>
void drawPrepared(CpuPreparedPieces<Piece>& prepared, CpuDepthBuffer& depth,
                  const RasterPass& raster, const CpuPieces& pieces, CpuPendingWrite& p,
                  BlockMask blocks, CpuTileWork& work) {
  if (p.firstPrepared == CpuPendingWrite::kNotSetUp) {
    const std::uint32_t first = prepared.room(pieces.count);
    PreparedWrite<Piece>* room = prepared.at(first);
    std::size_t n;
    if constexpr (std::is_same_v<Piece, ScreenQuad>)
      n = prepareWrites(depth, raster, {pieces.quads.data(), pieces.count}, room);
    else
      n = prepareWrites(depth, raster, {pieces.triangles.data(), pieces.count}, room,
                        pieces.extentsIfMade());
    p.firstPrepared = first;
    p.preparedCount = static_cast<std::uint32_t>(n);
    prepared.add(first, n);
    if (!p.counted) ++work.writesRasterised;
    p.counted = true;
  }
  writePrepared(depth, raster, {prepared.at(p.firstPrepared), p.preparedCount},
                blocks & p.remaining, work.raster, p.object);
}

// What evaluating a tile works on: its state and the thread's prepared pieces.
struct TileAt {
  CpuTileState& state;
  CpuPreparedScratch& prepared;
};

void drawPending(const TileAt& tile, const CpuScene& scene, CpuPendingWrite& p, BlockMask blocks,
                 CpuTileWork& work) {
  CpuTileState& state = tile.state;
  const CpuItem& item = p.run->bins.items[p.item];
  const RasterPass& raster = rasterOf(*p.run, item);
  CpuPieces pieces;
  if (p.firstPrepared == CpuPendingWrite::kNotSetUp) {
    piecesOf(scene, *p.run, item, state.depth, pieces);
    p.quads = pieces.areQuads;
  }
  if (p.quads)
    drawPrepared(tile.prepared.quads, state.depth, raster, pieces, p, blocks, work);
  else
    drawPrepared(tile.prepared.triangles, state.depth, raster, pieces, p, blocks, work);
  p.remaining &= ~blocks;
}

// Draws there the writes of group `g` pending in block `bit` (with `zHi`, only those whose nearest
// key is at most zHi); returns the nearest key of those that stay pending there (+infinity: none).
float drawGroup(const TileAt& tile, const CpuScene& scene, const CpuPendingGroup& g, BlockMask bit,
                CpuTileWork& work, std::optional<float> zHi = std::nullopt) {
  float stays = std::numeric_limits<float>::infinity();
  for (std::uint32_t w = g.firstWrite; w < g.endWrite; ++w) {
    CpuPendingWrite& p = tile.state.pending[w];
    if ((p.remaining & bit) == 0) continue;
    if (!zHi || p.kLo <= *zHi)
      drawPending(tile, scene, p, bit, work);
    else
      stays = std::min(stays, p.kLo);
  }
  return stays;
}

void drawAllPending(const TileAt& tile, const CpuScene& scene, CpuTileWork& work) {
  for (CpuPendingWrite& p : tile.state.pending)
    if (p.remaining != 0) drawPending(tile, scene, p, p.remaining, work);
}

// Block `b` with no write pending.
void emptyBlock(CpuTileState& state, std::size_t b) {
  state.pendingIn.clear(b);
  state.pendingNearest[b] = std::numeric_limits<float>::infinity();
  state.pendingOthers[b] = {};
  state.pendingBlocks &= ~(BlockMask{1} << b);
}

// No write pending any more.
void clearPending(CpuTileState& state) {
  for (BlockMask m = state.pendingBlocks; m != 0; m &= m - 1)
    emptyBlock(state, static_cast<std::size_t>(std::countr_zero(m)));
  state.pending.clear();
  state.groups.clear();
  state.groupOpen = false;
}

// No write pending any more, nor their prepared pieces.
void clearPending(const TileAt& tile) {
  clearPending(tile.state);
  tile.prepared.clear();
}

// The end of a tile's evaluation: the writes left pending give their prepared pieces back (a
// later fetch going on in the tile prepares them again), so the thread's storage serves its next
// tile.
void releasePrepared(const TileAt& tile) {
  for (CpuPendingWrite& p : tile.state.pending) p.firstPrepared = CpuPendingWrite::kNotSetUp;
  tile.prepared.clear();
}

// Draws every write pending in block `b` there.
void drawBlockPending(const TileAt& tile, const CpuScene& scene, std::size_t b, CpuTileWork& work) {
  tile.state.pendingIn.forEach(b, [&](std::uint32_t g) {
    drawGroup(tile, scene, tile.state.groups[g], BlockMask{1} << b, work);
  });
  emptyBlock(tile.state, b);
}

// The open group of pending writes put in its blocks' lists; a block with `mostInBlock` groups has
// them drawn instead, which leaves the same depths. Before anything reads the lists: a test, the
// end of the walk.
void closeGroup(const TileAt& tile, const CpuScene& scene, std::size_t mostInBlock,
                CpuTileWork& work) {
  CpuTileState& state = tile.state;
  if (!state.groupOpen) return;
  state.groupOpen = false;
  const auto index = static_cast<std::uint32_t>(state.groups.size() - 1);
  const CpuPendingGroup& group = state.groups[index];
  state.pendingBlocks |= group.blocks;
  // (Drawing a full block touches that block's depths and list only.)
  for (BlockMask m = group.blocks; m != 0; m &= m - 1) {
    const auto b = static_cast<std::size_t>(std::countr_zero(m));
    state.pendingIn.push(b, index);
    if (group.orderIndependent)
      state.pendingOthers[b].add(state.pendingNearest[b], group.kLo, group.object);
    state.pendingNearest[b] = std::min(state.pendingNearest[b], group.kLo);
    if (state.pendingIn.size(b) >= mostInBlock) drawBlockPending(tile, scene, b, work);
  }
  if (state.pendingBlocks == 0) clearPending(tile);
}

// A write made pending: it joins the open group when that holds writes of its command (no test was
// walked since: CpuPendingGroup), else the open group is closed and it starts one.
void addPending(const TileAt& tile, const CpuScene& scene, const CpuPendingWrite& write,
                std::uint32_t command, bool orderIndependent, std::size_t mostInBlock,
                CpuTileWork& work) {
  CpuTileState& state = tile.state;
  if (state.groupOpen &&
      (state.groups.back().command != command || state.groups.back().run != write.run))
    closeGroup(tile, scene, mostInBlock, work);
  if (!state.groupOpen) {
    const auto first = static_cast<std::uint32_t>(state.pending.size());
    state.groups.push_back({.object = write.object,
                            .command = command,
                            .orderIndependent = orderIndependent,
                            .run = write.run,
                            .firstWrite = first,
                            .endWrite = first});
    state.groupOpen = true;
  }
  CpuPendingGroup& group = state.groups.back();
  state.pending.push_back(write);
  group.blocks |= write.remaining;
  group.kLo = std::min(group.kLo, write.kLo);
  group.endWrite = static_cast<std::uint32_t>(state.pending.size());
}

// Whether pending group `g` can lie in front of a key `zHi` of a test of `object`: in an
// order-independent pass a test reads no write of its own object.
bool canOcclude(const CpuPendingGroup& g, float zHi, bool orderIndependent, std::uint32_t object) {
  return g.kLo <= zHi && !(orderIndependent && g.object == object);
}

// A key no farther than the nearest of the writes pending in block `b` that a test of `object`
// reads (in an order-independent pass not its own: if it has the nearest key, the others').
float nearestRead(const CpuTileState& state, std::size_t b, bool orderIndependent,
                  std::uint32_t object) {
  const CpuPendingOthers& others = state.pendingOthers[b];
  return orderIndependent && others.object == object ? others.nearest : state.pendingNearest[b];
}

// The blocks of `blocks` where a pending write can lie in front of a test (farthest key `kHi`).
BlockMask blocksReadingPending(const CpuTileState& state, BlockMask blocks, float kHi,
                               bool orderIndependent, std::uint32_t object) {
  BlockMask reading = 0;
  for (BlockMask m = blocks & state.pendingBlocks; m != 0; m &= m - 1) {
    const auto b = static_cast<std::size_t>(std::countr_zero(m));
    if (nearestRead(state, b, orderIndependent, object) <= kHi) reading |= BlockMask{1} << b;
  }
  return reading;
}

// Whether the pieces of an item answer one by one: the triangles of a batch (a box is one piece
// whatever it is drawn as).
bool answersEachTriangle(const CpuItem& item, const CpuPieces& pieces) {
  return item.answerEach && !pieces.areQuads && item.count > 1;
}

// Tests an item's pieces against what the tile holds (with `pending`: then again where pending
// writes it may read are, drawing those first, block by block) and clears the answers it finds
// occluded. With the early-out, a batch's triangles another tile found occluded, or whose gate
// is (CpuAnswers::open), are not tested, and their answers are cleared (a gated one's fetched
// answer is 0 whatever its own).
void testPieces(CpuDepthBuffer& depth, const CpuPieces& pieces, const RasterPass& raster,
                const CpuItem& item, std::uint32_t object, bool earlyOut, QueryIndex gateBack,
                CpuAnswers answers, CpuTileWork& work, PendingBlocks* pending = nullptr) {
  if (answersEachTriangle(item, pieces)) {
    std::uint8_t visible[kChunkTriangles];
    for (std::size_t i = 0; i < pieces.count; ++i)
      visible[i] = !earlyOut || answers.open(item.answer + pieces.offset[i], gateBack);
    testEachTriangle(depth, raster, {pieces.triangles.data(), pieces.count}, visible, work.raster,
                     object, pending, pieces.extentsIfMade());
    for (std::size_t i = 0; i < pieces.count; ++i)
      if (!visible[i]) answers.occlude(item.answer + pieces.offset[i]);
    return;
  }
  const bool occluded =
      pieces.areQuads
          ? testQuadsUntilOccluded(depth, raster, {pieces.quads.data(), pieces.count}, work.raster,
                                   object, pending) < pieces.count
          : testTrianglesUntilOccluded(depth, raster, {pieces.triangles.data(), pieces.count},
                                       work.raster, object, pending,
                                       pieces.extentsIfMade()) < pieces.count;
  if (occluded) answers.occlude(item.answer);
}

// A test drawing the pending writes of its tile it may read where its pieces reach, block by
// block (PendingBlocks::resolve).
struct TestResolution {
  TileAt tile;
  const CpuScene& scene;
  const CpuItem& item;
  std::uint32_t object;  // the item's
  bool orderIndependent;
  CpuTileWork& work;
};
bool resolveForTest(void* context, std::size_t block, float zHi) {
  auto& t = *static_cast<TestResolution*>(context);
  CpuTileState& state = t.tile.state;
  // Every write pending there behind the piece: none to draw, the list as it is.
  const float read = nearestRead(state, block, t.orderIndependent, t.object);
  if (read > zHi) return read <= t.item.kHi;
  const BlockMask bit = BlockMask{1} << block;
  bool left = false;
  float nearest = std::numeric_limits<float>::infinity();
  CpuPendingOthers others;
  state.pendingIn.keepIf(block, [&](std::uint32_t i) {
    const CpuPendingGroup& g = state.groups[i];
    if (!canOcclude(g, zHi, t.orderIndependent, t.object)) {
      // Behind this piece; maybe not behind a later one of the test.
      left = left || canOcclude(g, t.item.kHi, t.orderIndependent, t.object);
      if (t.orderIndependent) others.add(nearest, g.kLo, g.object);
      nearest = std::min(nearest, g.kLo);
      return true;
    }
    // Those of its writes pending here that can lie in front are drawn, the others stay (and the
    // block's nearest key is theirs).
    const float stays = drawGroup(t.tile, t.scene, g, bit, t.work, zHi);
    if (stays == std::numeric_limits<float>::infinity()) return false;
    left = left || stays <= t.item.kHi;
    if (t.orderIndependent) others.add(nearest, stays, g.object);
    nearest = std::min(nearest, stays);
    return true;
  });
  state.pendingNearest[block] = nearest;
  state.pendingOthers[block] = others;
  if (state.pendingIn.size(block) == 0) state.pendingBlocks &= ~bit;
  return left;
}

// A pass of the other depth order goes on in the buffer (a SharedSecond pass after its
// SharedFirst). Writes pending from before are older than everything to come; when all their keys
// lie behind the new pass' whole range, no test of it can find them in front and every write of
// it overwrites them, so they are dropped; otherwise they are drawn now, in order, before
// anything of the new pass.
void enterPass(const TileAt& tile, const CpuScene& scene, const RasterPass& raster,
               CpuTileWork& work) {
  CpuTileState& state = tile.state;
  if (state.sign == raster.sign) return;
  if (state.sign != 0.f) {
    bool behind = true;
    for (const CpuPendingWrite& p : state.pending) {
      if (p.remaining == 0) continue;
      // Stored values of its keys, then their nearest key in the new order.
      const float vLo = state.sign > 0 ? p.kLo : -p.kHi, vHi = state.sign > 0 ? p.kHi : -p.kLo;
      const float nearest = raster.sign > 0 ? vLo : -vHi;
      behind = behind && nearest > raster.keyHi;
    }
    if (!behind) drawAllPending(tile, scene, work);
    clearPending(tile);
  }
  state.sign = raster.sign;
}

// A write item met in a tile's walk: drawn (plain evaluation), dropped where it changes nothing,
// or made pending.
void walkWrite(const TileAt& at, const CpuScene& scene, const CpuRun& run, std::uint32_t i,
               const PixelRect& inTile, const CpuEvaluation& evaluation, CpuTileWork& work) {
  CpuTileState& state = at.state;
  const CpuItem& item = run.bins.items[i];
  const RasterPass& raster = rasterOf(run, item);
  enterPass(at, scene, raster, work);
  ++work.writes;
  if (!evaluation.demandDriven) {
    writeItem(state.depth, scene, run, item, work);
    return;
  }
  const BlockMask blocks = blocksUnder(state.depth, item.rect.within(inTile));
  // At or behind everything stored under it (pending writes only add nearer keys): it changes
  // nothing.
  if (storedDecides<false>(state.depth, blocks, raster.sign, item.kLo)) return;
  // A pending write keeps its prepared pieces: a tile with this many (thousands of node boxes in
  // one tile at a low resolution) has them drawn instead, which leaves the same depths.
  if (state.pending.size() >= evaluation.mostPendingInTile) {
    drawAllPending(at, scene, work);
    clearPending(at);
  }
  addPending(at, scene, {blocks, item.kLo, item.kHi, objectOf(run, item), &run, i}, item.command,
             raster.orderIndependent, evaluation.mostPendingInBlock, work);
}

}  // namespace

CpuTileWork& CpuTileWork::operator+=(const CpuTileWork& o) {
  raster += o.raster;
  tests += o.tests, testsByBounds += o.testsByBounds, testsSkipped += o.testsSkipped;
  writes += o.writes, writesRasterised += o.writesRasterised;
  return *this;
}

void startTile(CpuTileState& state, const CpuChain& chain, std::uint32_t tile, float clearValue,
               std::uint64_t chainId) {
  const int blocks = chain.tileSize / kBlock;
  const int tx = static_cast<int>(tile % chain.tilesX), ty = static_cast<int>(tile / chain.tilesX);
  state.depth.place(chain.resolution, tx * blocks, ty * blocks, blocks, blocks,
                    chain.orderIndependent);
  state.depth.clear(clearValue);
  clearPending(state);
  state.sign = 0.f;
  state.chain = chainId;
  state.rest = {};
}

void evaluateTile(CpuTileState& state, const CpuScene& scene, const CpuRun& run,
                  std::uint32_t chain, std::uint32_t tile, const CpuEvaluation& evaluation,
                  CpuAnswers answers, CpuPreparedScratch& prepared, CpuTileWork& work) {
  const TileAt at{state, prepared};
  const PixelRect inTile = tileRect(state.depth);
  // A pass going on in the buffer after a fetch: first the writes its last walk left out.
  if (state.rest.run != nullptr) {
    const CpuTileState::Rest rest = std::exchange(state.rest, {});
    const std::span<const std::uint32_t> left = rest.run->bins.chains[rest.chain].itemsOf(tile);
    for (std::size_t n = rest.from; n < left.size(); ++n)
      if (const CpuItem& item = rest.run->bins.items[left[n]]; !item.test)
        walkWrite(at, scene, *rest.run, left[n], inTile, evaluation, work);
  }
  std::span<const std::uint32_t> items = run.bins.chains[chain].itemsOf(tile);
  // Nothing after the tile's last test still open can change an answer, so the walk stops there
  // (the writes after it would be made pending, or drawn, for no test). Only a later pass going on
  // in the buffer (of the run's last chain, CpuRasterBackend::flush) could read them: they are
  // walked before it (state.rest).
  if (evaluation.demandDriven && evaluation.earlyOut) {
    std::size_t end = items.size();
    for (; end > 0; --end) {
      const CpuItem& item = run.bins.items[items[end - 1]];
      if (item.test && !answered(item, answers, gateBackOf(run, item))) break;
    }
    if (end < items.size() && chain + 1 == run.bins.chainCount)
      state.rest = {&run, chain, static_cast<std::uint32_t>(end)};
    items = items.first(end);
  }
  for (std::size_t n = 0; n < items.size(); ++n) {
    const std::uint32_t i = items[n];
    // (A tile's items lie scattered in the recording's: the next few are fetched ahead, and the
    // screen form of a box among them once its item is at hand.)
    if (n + 8 < items.size()) __builtin_prefetch(&run.bins.items[items[n + 8]]);
    if (n + 4 < items.size()) {
      const CpuItem& ahead = run.bins.items[items[n + 4]];
      if (ahead.box) {
        const auto* cube = reinterpret_cast<const char*>(&run.bins.boxCubes[ahead.first]);
        __builtin_prefetch(cube), __builtin_prefetch(cube + sizeof(ScreenMatrix) - 1);
      }
    }
    const CpuItem& item = run.bins.items[i];
    if (!item.test) {
      walkWrite(at, scene, run, i, inTile, evaluation, work);
      continue;
    }
    const RasterPass& raster = rasterOf(run, item);
    enterPass(at, scene, raster, work);
    ++work.tests;
    // (A gated test's gates are final here: its chain runs after theirs, CpuRasterBackend.)
    const QueryIndex gateBack = evaluation.earlyOut ? gateBackOf(run, item) : QueryIndex{0};
    if (evaluation.earlyOut && answered(item, answers, gateBack)) {
      ++work.testsSkipped;
      continue;
    }
    const BlockMask blocks =
        evaluation.demandDriven ? blocksUnder(state.depth, item.rect.within(inTile)) : BlockMask{0};
    const std::uint32_t object = objectOf(run, item);
    closeGroup(at, scene, evaluation.mostPendingInBlock, work);
    const BlockMask reading =
        blocksReadingPending(state, blocks, item.kHi, raster.orderIndependent, object);
    const bool readsPending = reading != 0;
    if (evaluation.demandDriven && !readsPending &&
        storedDecides<true>(state.depth, blocks, raster.sign, item.kHi)) {
      ++work.testsByBounds;
      continue;
    }
    // (About half of env2's node box tests in `cullide_bvh` end here, their faces never set up.)
    if (evaluation.demandDriven && item.box &&
        occludedAtCentre(state.depth, run.bins.boxCubes[item.first], raster, item.kLo, inTile)) {
      ++work.testsByBounds;
      answers.occlude(item.answer);
      continue;
    }
    CpuPieces pieces;
    piecesOf(scene, run, item, state.depth, pieces);
    if (!readsPending) {
      testPieces(state.depth, pieces, raster, item, object, evaluation.earlyOut, gateBack, answers,
                 work);
      continue;
    }
    // Against what the tile holds first: occluded there, the pending writes stay pending. Visible
    // there, the blocks with pending writes it may read are tested again, each once the writes
    // that can lie in front of the test's piece are drawn there, until a piece is occluded. (The
    // two steps share each piece's set-up; a batch's triangles take both one triangle at a time.)
    TestResolution resolution{at, scene, item, object, raster.orderIndependent, work};
    PendingBlocks unresolved{reading, reading, resolveForTest, &resolution};
    testPieces(state.depth, pieces, raster, item, object, evaluation.earlyOut, gateBack, answers,
               work, &unresolved);
    if (state.pendingBlocks == 0) clearPending(at);
  }
  closeGroup(at, scene, evaluation.mostPendingInBlock, work);
  releasePrepared(at);
}

void rasteriseWrites(CpuTileState& state, const CpuScene& scene, const CpuRun& run,
                     std::span<const std::uint32_t> items, CpuTileWork& work) {
  for (const std::uint32_t i : items) {
    const CpuItem& item = run.bins.items[i];
    if (!item.test) writeItem(state.depth, scene, run, item, work);
  }
}

}  // namespace cdb
