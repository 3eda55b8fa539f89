#include "culling/visibility/cpu/CpuRasterBackend.h"

#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "core/Errors.h"
#include "culling/visibility/DrawChecks.h"
#include "culling/visibility/cpu/CpuPassSpace.h"
#include "culling/visibility/cpu/CpuRasteriser.h"

namespace cdb {

// Binning's pixel rectangles (PixelRect) hold a frame's pixel coordinates in 16 bits.
static_assert(CpuRasterBackend::kMaxResolution - 1 <= std::numeric_limits<std::int16_t>::max());

namespace {

// The slot of `object`'s last command in `role` in a table per object and role (1 + its index in
// the recording; 0: none yet), grown to the scene's `objects` first.
std::uint32_t& lastInRole(std::vector<std::uint32_t>& table, std::size_t objects, ObjectId object,
                          CpuCommand::Role role) {
  if (table.size() < 2 * objects) table.resize(2 * objects, 0);
  return table[2 * object + (role == CpuCommand::Role::Write ? 1 : 0)];
}

// 1 + `object`'s last command in either role of such a table (0: none yet).
std::uint32_t lastInEitherRole(std::vector<std::uint32_t>& table, std::size_t objects,
                               ObjectId object) {
  return std::max(lastInRole(table, objects, object, CpuCommand::Role::Test),
                  lastInRole(table, objects, object, CpuCommand::Role::Write));
}

bool sameMatrix(const CpuCommand& a, const CpuCommand& b) {
  return std::memcmp(a.toScreen.data(), b.toScreen.data(), sizeof(ScreenMatrix)) == 0;
}

// What a command copies items from when it draws what command `i` of the recording drew: the
// command `i` copies from, or `i`.
std::uint32_t itemsSource(const CpuRecording& recording, std::uint32_t i) {
  const CpuCommand& c = recording.commands[i];
  return c.itemsOf != CpuCommand::kNone ? c.itemsOf : i;
}

}  // namespace

CpuRasterBackend::CpuRasterBackend(const VisibilityOptions& options) {
  open_ = freshRun();
  setOptions(options);
}

CpuRasterBackend::~CpuRasterBackend() = default;

std::string CpuRasterBackend::renderer() const {
  return std::string("cpu depth rasteriser (Highway ") + rasteriserTarget() + ", " +
         std::to_string(threads_) + (threads_ == 1 ? " thread)" : " threads)");
}

void CpuRasterBackend::setOptions(const VisibilityOptions& options) {
  flush();  // what was drawn so far keeps the options it was drawn with
  options_ = options;
  const int threads = options.threads > 0 ? options.threads : tbb::info::default_concurrency();
  if (!arena_ || threads != threads_) {
    threads_ = std::max(threads, 1);
    arena_ = std::make_unique<tbb::task_arena>(threads_);
  }
}

void CpuRasterBackend::setEvaluation(const CpuEvaluation& evaluation) {
  if (evaluation.tileSize < 0 || evaluation.tileSize % CpuDepthBuffer::kBlock != 0)
    throw InputError("cpu backend tile size " + std::to_string(evaluation.tileSize) +
                     " is not 0 or a positive multiple of 8 pixels");
  if (evaluation.demandDriven && (evaluation.tileSize == 0 || evaluation.tileSize > 64))
    throw InputError("cpu backend tile size " + std::to_string(evaluation.tileSize) +
                     " is not 8..64 pixels, as a demand-driven evaluation needs");
  flush();
  evaluation_ = evaluation;
}

void CpuRasterBackend::attachScene(const SceneGeometry& scene) {
  flush();
  checkSceneIndices(scene);
  releaseRetained();  // its pending writes drew the old scene's meshes
  scene_ = &scene;
  meshBounds_ = meshBoundsOf(scene);
  poses_.assign(scene.objectCount(), Eigen::Matrix4d::Identity());
  sequence_.newScene();
}

void CpuRasterBackend::setPoses(std::span<const Pose> poses) {
  checkPoseCount(scene_, poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) poses_[i] = poses[i].matrix();
}

CpuPass CpuRasterBackend::passFor(const DepthPassSetup& setup) const {
  CpuPass pass;
  pass.raster = rasterPassOf(setup, options_, sequence_.depth() == DepthUse::OrderIndependent);
  pass.clears = setup.clear;
  pass.clearValue = static_cast<float>(setup.clearDepth);
  return pass;
}

void CpuRasterBackend::beginPass(const ViewSpec& view, DepthUse depth) {
  if (!scene_) throw RunError("a visibility pass began before a scene was attached");
  sequence_.checkBegin(view, depth);
  const DepthPassSetup setup = makeDepthPassSetup(view, depth);
  if (setup.resolution > kMaxResolution)
    throw InputError("resolution " + std::to_string(setup.resolution) + " is outside 1.." +
                     std::to_string(kMaxResolution) + " (the CPU rasteriser's largest buffer)");
  setup_ = setup;
  worldToKey_ = worldToKeyOf(setup);
  sequence_.begin(view, depth);
  CpuPass pass = passFor(setup);
  // Its SharedFirst already ran: it goes on in the buffer that pass left.
  const bool first = open_->recording.passes.empty();
  pass.continues = depth == DepthUse::SharedSecond && first;
  if (first && !pass.continues) reuseRetainedRun();
  CpuRecording& recording = open_->recording;
  pass.firstCommand = static_cast<std::uint32_t>(recording.commands.size());
  recording.passes.push_back(pass);
  inPass_ = true;
  ++counters_.passes;
  if (setup.clear) ++counters_.depthClears;
}

CpuCommand& CpuRasterBackend::record(CpuCommand::Role role, CpuCommand::Source source,
                                     ObjectId object) {
  CpuRecording& recording = open_->recording;
  if (recording.passes.empty()) {
    // Draws after a fetch without a new pass go on in the open pass.
    CpuPass pass = passFor(setup_);
    pass.clears = false;
    pass.continues = true;
    pass.firstCommand = static_cast<std::uint32_t>(recording.commands.size());
    recording.passes.push_back(pass);
  }
  // (Binning numbers a recording's commands in CpuItem::command's bits.)
  if (recording.commands.size() >= CpuItem::kMostCommands)
    throw std::length_error("cpu backend: more than " + std::to_string(CpuItem::kMostCommands) +
                            " draws between two fetches");
  sequence_.draw(role == CpuCommand::Role::Test);
  CpuCommand& c = recording.commands.emplace_back();
  c.role = role;
  c.source = source;
  c.object = object;
  c.mesh = scene_->objects[object].mesh;
  c.toScreen = worldToKey_ * poses_[object];
  return c;
}

CpuCommand& CpuRasterBackend::recordRange(CpuCommand::Role role, const MeshRange& range) {
  const std::uint32_t mesh = scene_->objects[range.object].mesh;
  if (range.firstTriangle != 0 || range.triangleCount != scene_->meshes[mesh].triangleCount()) {
    // Part of a mesh: its triangles listed (draw order is over whole meshes).
    std::vector<std::uint32_t>& part = partScratch_;
    part.resize(range.triangleCount);
    std::iota(part.begin(), part.end(), range.firstTriangle);
    return recordListed(role, range.object, part);
  }
  CpuRecording& recording = open_->recording;
  CpuCommand& c = record(role, CpuCommand::Source::Range, range.object);
  c.first = 0, c.count = range.triangleCount;
  c.winding = meshBounds_[mesh].winding;
  // The object's mesh drawn again in the same role under the same matrix (CULLIDE's two passes
  // of a view): its items are copied at binning.
  std::uint32_t& sameRole =
      lastInRole(recording.lastRange, scene_->objectCount(), range.object, role);
  if (sameRole != 0 && sameMatrix(recording.commands[sameRole - 1], c))
    c.itemsOf = itemsSource(recording, sameRole - 1);
  sameRole = static_cast<std::uint32_t>(recording.commands.size());
  ++counters_.draws;
  counters_.trianglesDrawn += range.triangleCount;
  return c;
}

CpuCommand& CpuRasterBackend::recordListed(CpuCommand::Role role, ObjectId object,
                                           std::span<const std::uint32_t> triangles) {
  CpuRecording& recording = open_->recording;
  auto& listed = recording.listed;
  CpuCommand& c = record(role, CpuCommand::Source::Listed, object);
  c.count = static_cast<std::uint32_t>(triangles.size());
  // The same list as the object's last one (a batch test and the write of its triangles, both of
  // CULLIDE's passes of a view) is recorded and put in draw order once; the items of a command of
  // the same role under the same matrix are copied at binning. Compared entry for entry.
  const auto index = static_cast<std::uint32_t>(recording.commands.size() - 1);
  const auto rootOf = [&](std::uint32_t i) {
    const CpuCommand& earlier = recording.commands[i];
    return earlier.listedOf != CpuCommand::kNone ? earlier.listedOf : i;
  };
  const std::uint32_t latest =
      lastInEitherRole(recording.lastListed, scene_->objectCount(), object);
  std::uint32_t& sameRole = lastInRole(recording.lastListed, scene_->objectCount(), object, role);
  if (latest != 0) {
    const CpuCommand& earlier = recording.commands[latest - 1];
    if (earlier.count == c.count &&
        std::memcmp(listed.data() + earlier.first, triangles.data(), triangles.size_bytes()) == 0) {
      c.first = earlier.first;
      c.listedOf = rootOf(latest - 1);
    }
  }
  if (c.listedOf != CpuCommand::kNone && sameRole != 0 && rootOf(sameRole - 1) == c.listedOf &&
      sameMatrix(recording.commands[sameRole - 1], c))
    c.itemsOf = itemsSource(recording, sameRole - 1);
  sameRole = index + 1;
  if (c.listedOf == CpuCommand::kNone) {
    c.first = static_cast<std::uint32_t>(listed.size());
    listed.append(triangles.begin(), triangles.end());
  }
  ++counters_.draws;
  counters_.trianglesDrawn += triangles.size();
  return c;
}

CpuCommand& CpuRasterBackend::recordBoxes(CpuCommand::Role role, ObjectId object,
                                          std::span<const OrientedBox> boxes) {
  CpuRecording& recording = open_->recording;
  auto& all = recording.boxes;
  CpuCommand& c = record(role, CpuCommand::Source::Boxes, object);
  c.count = static_cast<std::uint32_t>(boxes.size());
  // The same boxes as the object's last box command under the same matrix (a node's test and
  // write, both passes of a view) are recorded once: binning then bounds them, and a tile sets
  // them up, from one screen form. Compared bit for bit, so every piece is the same.
  static_assert(sizeof(OrientedBox) == 15 * sizeof(double), "a box has no padding to compare");
  const auto index = static_cast<std::uint32_t>(recording.commands.size() - 1);
  const auto rootOf = [&](std::uint32_t i) {
    const CpuCommand& earlier = recording.commands[i];
    return earlier.sharesBoxes() ? earlier.boxesOf : i;
  };
  const std::uint32_t latest =
      lastInEitherRole(recording.lastBoxes, scene_->objectCount(), object);
  std::uint32_t& sameRole = lastInRole(recording.lastBoxes, scene_->objectCount(), object, role);
  if (latest != 0) {
    const CpuCommand& earlier = recording.commands[latest - 1];
    if (earlier.count == c.count && sameMatrix(earlier, c) &&
        std::memcmp(all.data() + earlier.first, boxes.data(), boxes.size_bytes()) == 0) {
      c.first = earlier.first;
      c.boxesOf = rootOf(latest - 1);
    }
  }
  // The items of the last command of the same role with these boxes (the other pass of a view)
  // are copied at binning.
  if (c.sharesBoxes() && sameRole != 0 && rootOf(sameRole - 1) == c.boxesOf)
    c.itemsOf = itemsSource(recording, sameRole - 1);
  sameRole = index + 1;
  if (!c.sharesBoxes()) {
    c.first = static_cast<std::uint32_t>(all.size());
    all.append(boxes.begin(), boxes.end());
  }
  ++counters_.draws;
  counters_.trianglesDrawn += 12u * boxes.size();  // a box is the cube's 12 triangles, as on GL
  return c;
}

QueryIndex CpuRasterBackend::issue(std::uint32_t count) {
  const QueryIndex first = issued_;
  issued_ += count;
  counters_.queries += count;
  return first;
}

QueryIndex CpuRasterBackend::queryRange(const MeshRange& range) {
  checkRangeDrawn(scene_, range, inPass_);
  const QueryIndex q = issue(1);
  if (range.triangleCount == 0) return q;  // no sample: fully visible
  recordRange(CpuCommand::Role::Test, range).query = q;
  return q;
}

QueryIndex CpuRasterBackend::queryBox(ObjectId object, const OrientedBox& localBox) {
  return queryBoxes(object, std::span<const OrientedBox>(&localBox, 1));
}

// A batch: one draw, an answer per triangle or box.
QueryIndex CpuRasterBackend::queryTriangles(const MeshRange& range) {
  checkRangeDrawn(scene_, range, inPass_);
  if (range.triangleCount == 0) return kNoQuery;
  const QueryIndex q = issue(range.triangleCount);
  CpuCommand& c = recordRange(CpuCommand::Role::Test, range);
  c.query = q, c.answerEach = true;
  c.winding = 0;  // every triangle answers for itself, those facing the viewer too
  return q;
}

QueryIndex CpuRasterBackend::queryTriangles(ObjectId object,
                                            std::span<const std::uint32_t> triangles) {
  checkListedDrawn(scene_, object, triangles, inPass_);
  if (triangles.empty()) return kNoQuery;
  const QueryIndex q = issue(static_cast<std::uint32_t>(triangles.size()));
  CpuCommand& c = recordListed(CpuCommand::Role::Test, object, triangles);
  c.query = q, c.answerEach = true;
  return q;
}

QueryIndex CpuRasterBackend::queryBoxes(ObjectId object, std::span<const OrientedBox> localBoxes) {
  checkObjectDrawn(scene_, object, inPass_);
  if (localBoxes.empty()) return kNoQuery;
  const QueryIndex q = issue(static_cast<std::uint32_t>(localBoxes.size()));
  CpuCommand& c = recordBoxes(CpuCommand::Role::Test, object, localBoxes);
  c.query = q, c.answerEach = true;
  return q;
}

void CpuRasterBackend::writeRange(const MeshRange& range) {
  checkRangeDrawn(scene_, range, inPass_);
  if (range.triangleCount != 0) recordRange(CpuCommand::Role::Write, range);
}

void CpuRasterBackend::writeTriangles(ObjectId object, std::span<const std::uint32_t> triangles) {
  checkListedDrawn(scene_, object, triangles, inPass_);
  if (!triangles.empty()) recordListed(CpuCommand::Role::Write, object, triangles);
}

void CpuRasterBackend::writeBox(ObjectId object, const OrientedBox& localBox) {
  writeBoxes(object, std::span<const OrientedBox>(&localBox, 1));
}

void CpuRasterBackend::writeBoxes(ObjectId object, std::span<const OrientedBox> localBoxes) {
  checkObjectDrawn(scene_, object, inPass_);
  if (!localBoxes.empty()) recordBoxes(CpuCommand::Role::Write, object, localBoxes);
}

void CpuRasterBackend::gateSet(QueryIndex gated, QueryIndex gate, std::uint32_t count) {
  CpuRecording& recording = open_->recording;
  // The test commands holding both answers, searched from the last (a strategy gates a query
  // just issued by one of a pass before, a few commands per object back).
  constexpr std::size_t kSearched = 4096;
  const auto commandOf = [&](QueryIndex q) {
    const std::size_t n = recording.commands.size();
    for (std::size_t i = n; i-- > 0 && n - i <= kSearched;) {
      const CpuCommand& c = recording.commands[i];
      if (c.role == CpuCommand::Role::Test && c.query == q) return static_cast<std::uint32_t>(i);
    }
    return CpuCommand::kNone;
  };
  const std::uint32_t gatedAt = commandOf(gated), gateAt = commandOf(gate);
  if (gatedAt == CpuCommand::kNone || gateAt == CpuCommand::kNone) return;
  CpuCommand& c = recording.commands[gatedAt];
  const CpuCommand& g = recording.commands[gateAt];
  const auto answersOf = [](const CpuCommand& x) { return x.answerEach ? x.count : 1u; };
  // The same pieces in the same order: the same object's mesh, list entries or boxes (a command
  // drawing what an earlier one drew shares its `first`; boxes recorded again under another
  // matrix, as by the passes of depth-sorted culling, which look opposite ways, are compared bit
  // for bit), each answering alike, all gated.
  const auto sameBoxes = [&] {
    return c.source == CpuCommand::Source::Boxes &&
           std::memcmp(recording.boxes.data() + c.first, recording.boxes.data() + g.first,
                       std::size_t{c.count} * sizeof(OrientedBox)) == 0;
  };
  const bool same = c.object == g.object && c.source == g.source && c.count == g.count &&
                    c.answerEach == g.answerEach && (c.first == g.first || sameBoxes());
  if (!same || answersOf(c) != count) return;
  c.gateCommand = gateAt;
  c.gateBack = gated - gate;
}

std::shared_ptr<CpuRun> CpuRasterBackend::freshRun() {
  std::shared_ptr<CpuRun> run;
  if (!spareRuns_.empty()) {
    run = std::move(spareRuns_.back());
    spareRuns_.pop_back();
  } else {
    run = std::make_shared<CpuRun>();
  }
  run->recording.clear();
  return run;
}

void CpuRasterBackend::reuseRetainedRun() {
  // The buffer the last run left is not gone on in: its runs are free now, not at the next flush,
  // and the open (still empty) recording is made in the run retained last, whose tables are as
  // large as a recording like the last one needed. Otherwise two runs would alternate and each
  // grow its tables to the largest recording, on fresh pages.
  if (retained_.runs.empty()) return;
  releaseRetained();
  if (spareRuns_.empty() || !open_->recording.empty()) return;
  std::swap(open_, spareRuns_.back());
  open_->recording.clear();
}

void CpuRasterBackend::releaseRetained() {
  for (auto& [run, chain] : retained_.runs)
    if (run.use_count() == 1) spareRuns_.push_back(std::const_pointer_cast<CpuRun>(run));
  retained_.runs.clear();
  retained_.chainId = 0;
}

void CpuRasterBackend::flush() {
  if (open_->recording.empty()) return;
  storedTileIndex_ = -1;
  CpuRun& run = *open_;
  CpuRecording& recording = run.recording;
  recording.close();
  const bool continues = recording.passes[0].continues;
  if (continues && retained_.runs.empty())
    throw RunError("a pass went on after a fetch without a depth buffer to go on in");
  const int continuedTileSize =
      continues ? retained_.runs.front().first->bins.chains[retained_.runs.front().second].tileSize
                : 0;
  tbb::task_arena* arena = threads_ > 1 ? arena_.get() : nullptr;
  putInDrawOrder(recording, meshBounds_, orderScratch_);
  run.vertexSets.assign(recording, meshBounds_);
  binRecording(recording, meshBounds_, run.vertexSets, evaluation_.tileSize, continuedTileSize,
               arena, run.bins);
  answers_.resize(issued_, 1);

  // Where each chain's tiles live: a continued chain in the store that holds it, the last chain
  // (the buffer a later pass may go on in) in the other one, the rest in per-thread scratch.
  const auto& chains = run.bins.chains;
  const std::size_t chainCount = run.bins.chainCount;
  const std::size_t last = chainCount - 1;
  std::vector<ChainPlace>& place = chainPlaces_;
  place.assign(chainCount, ChainPlace{});
  for (std::size_t c = 0; c < chainCount; ++c) {
    const bool continued = c == 0 && continues;
    place[c].id = continued ? retained_.chainId : nextChainId_++;
    place[c].clearValue = continued ? retained_.clearValue : chains[c].clearValue;
    if (continued) place[c].store = retained_.store;
  }
  if (place[last].store < 0) {
    place[last].store = 1 - retained_.store;
    const std::size_t tiles = static_cast<std::size_t>(chains[last].tilesX) * chains[last].tilesX;
    if (stores_[place[last].store].size() < tiles) stores_[place[last].store].resize(tiles);
  }

  // Chains are evaluated in phases: a chain holding a test gated by one of an earlier chain of
  // the same phase starts the next, so that its gates' answers are final when its tiles run.
  chainOfPass_.resize(recording.passes.size());
  for (std::uint32_t c = 0; c < chainCount; ++c)
    for (std::uint32_t p = chains[c].firstPass; p < chains[c].endPass; ++p) chainOfPass_[p] = c;
  const auto startsPhase = [&](std::uint32_t chain, std::uint32_t phaseStart) {
    const CpuChain& k = chains[chain];
    for (std::uint32_t i = recording.passes[k.firstPass].firstCommand;
         i < recording.passes[k.endPass - 1].endCommand; ++i) {
      const CpuCommand& c = recording.commands[i];
      if (c.gateCommand == CpuCommand::kNone) continue;
      const std::uint32_t gateChain = chainOfPass_[run.bins.passOf[c.gateCommand]];
      if (gateChain >= phaseStart && gateChain < chain) return true;
    }
    return false;
  };
  for (CpuTileWork& w : work_) w = {};
  const CpuAnswers answers(answers_.data());
  const auto runUnit = [&](std::size_t u) {
    const auto [c, t] = units_[u];
    const ChainPlace& at = place[c];
    CpuTileState& state = at.store >= 0 ? stores_[at.store][t] : scratch_.local();
    if (at.store < 0 || state.chain != at.id) startTile(state, chains[c], t, at.clearValue, at.id);
    evaluateTile(state, CpuScene{*scene_, meshBounds_}, run, c, t, evaluation_, answers,
                 prepared_.local(), work_.local());
  };
  for (std::uint32_t phaseStart = 0; phaseStart < chainCount;) {
    std::uint32_t phaseEnd = phaseStart + 1;
    while (phaseEnd < chainCount && !startsPhase(phaseEnd, phaseStart)) ++phaseEnd;
    // A later phase's chains are binned once the phases before ran: tests their gates (or other
    // tiles) closed by then are left out of the tiles' lists, counted as tested and skipped.
    const bool leaveClosedOut = phaseStart > 0 && evaluation_.earlyOut;
    const std::uint64_t leftOut = binChains(recording, run.bins, phaseStart, phaseEnd, arena,
                                            leaveClosedOut ? &answers : nullptr);
    counters_.tileTests += leftOut;
    counters_.tileTestsSkipped += leftOut;
    units_.clear();
    for (std::uint32_t c = phaseStart; c < phaseEnd; ++c)
      for (const std::uint32_t t : chains[c].tilesUsed) units_.emplace_back(c, t);
    if (arena && units_.size() > 1) {
      arena->execute([&] { tbb::parallel_for(std::size_t{0}, units_.size(), runUnit); });
    } else {
      for (std::size_t u = 0; u < units_.size(); ++u) runUnit(u);
    }
    phaseStart = phaseEnd;
  }
  answersInIssueOrder(recording, meshBounds_, answers_.data(), answerScratch_);
  CpuTileWork total;
  for (const CpuTileWork& w : work_) total += w;
  counters_.pixelsTested += total.raster.pixelsTested;
  counters_.pixelsWritten += total.raster.pixelsWritten;
  counters_.tileTests += total.tests;
  counters_.tileTestsByBounds += total.testsByBounds;
  counters_.tileTestsSkipped += total.testsSkipped;
  counters_.tileWrites += total.writes;
  counters_.tileWritesRasterised += total.writesRasterised;

  // The last chain's buffer is where a pass may go on; the recording stays while it does.
  if (!(last == 0 && continues)) {
    releaseRetained();
    retained_.chainId = place[last].id;
    retained_.clearValue = place[last].clearValue;
    retained_.store = place[last].store;
  }
  retained_.runs.emplace_back(open_, static_cast<std::uint32_t>(last));
  open_ = freshRun();
}

void CpuRasterBackend::fetchAnswers(std::vector<std::uint8_t>& fullyVisible) {
  flush();
  if (issued_ > 0) ++counters_.fetches;
  answers_.resize(issued_, 1);
  fullyVisible.assign(answers_.begin(), answers_.end());
  answers_.clear();
  issued_ = 0;
}

float CpuRasterBackend::storedDepth(int x, int y) {
  flush();
  const CpuChain* chain =
      retained_.runs.empty()
          ? nullptr
          : &retained_.runs.front().first->bins.chains[retained_.runs.front().second];
  if (!chain || x < 0 || y < 0 || x >= chain->resolution || y >= chain->resolution)
    throw RunError("no depth buffer holds pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                   ")");
  const std::int64_t tile =
      static_cast<std::int64_t>(y / chain->tileSize) * chain->tilesX + x / chain->tileSize;
  if (tile != storedTileIndex_) {
    // Every write of the buffer drawn again, in order, into a fresh tile.
    startTile(storedTile_, *chain, static_cast<std::uint32_t>(tile), retained_.clearValue, 0);
    CpuTileWork ignored;
    for (const auto& [run, c] : retained_.runs)
      rasteriseWrites(storedTile_, CpuScene{*scene_, meshBounds_}, *run,
                      run->bins.chains[c].itemsOf(static_cast<std::uint32_t>(tile)), ignored);
    storedTileIndex_ = tile;
  }
  return storedTile_.depth.at(x, y);
}

}  // namespace cdb
