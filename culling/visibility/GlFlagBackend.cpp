#include "culling/visibility/GlFlagBackend.h"

#include <algorithm>
#include <chrono>
#include <string>

#include "core/Errors.h"
#include "culling/visibility/FlagShaders.h"
#include "render/HeadlessGlContext.h"

namespace cdb {

namespace {
constexpr std::size_t kFloatsPerMatrix = 16;
constexpr std::size_t kWordsPerSegment = 4;
}  // namespace

GlFlagBackend::GlFlagBackend(HeadlessGlContext& context, const VisibilityOptions& options)
    : context_(&context),
      pipeline_(context, PipelinePrograms::Flags),
      flags_(kItemFlagBinding),
      listedTriangles_(kListedTriangleBinding, sizeof(std::uint32_t)),
      boxMatrices_(kBoxMatrixBinding, kFloatsPerMatrix * sizeof(float)),
      passSegments_(kPassSegmentBinding, kWordsPerSegment * sizeof(std::uint32_t)) {
  setOptions(options);
}

GlFlagBackend::~GlFlagBackend() {
  try {
    context_->makeCurrent();
  } catch (const RunError&) {
    // The context is gone or unusable: its objects went with it.
  }
}

std::string GlFlagBackend::renderer() const { return context_->info().glRenderer; }

void GlFlagBackend::setOptions(const VisibilityOptions& options) {
  // What an order-independent pass gathered is drawn with the options it was issued under.
  if (orderIndependent_) drawPassTests();
  pipeline_.setConservative(options.conservative);
  pipeline_.setRawDepthOffset(options.rawDepthOffset);
  pipeline_.timeDraws(options.timeGpu);
}

void GlFlagBackend::attachScene(const SceneGeometry& scene) { pipeline_.attach(scene); }

void GlFlagBackend::setPoses(std::span<const Pose> poses) { pipeline_.uploadPoses(poses); }

void GlFlagBackend::beginPass(const ViewSpec& view, DepthUse depth) {
  // The previous pass' tests are answered against its buffers, before the clear. Writes that no
  // test of theirs read are not drawn.
  if (orderIndependent_) drawPassTests();
  orderIndependent_ = false;
  passWrites_.clear();
  passTests_.clear();
  const DepthPassSetup setup = pipeline_.beginCheckedPass(view, depth);
  orderIndependent_ = depth == DepthUse::OrderIndependent;
  testedInPass_ = false;
  writesDrawn_ = 0;
  // Another pipeline on the context may have bound its own buffers since the last pass.
  flags_.bind();
  listedTriangles_.bind();
  boxMatrices_.bind();
  passSegments_.bind();
  ++counters_.passes;
  if (setup.clear) ++counters_.depthClears;
}

void GlFlagBackend::drawRange(const MeshRange& range, DrawRole role, std::uint32_t item,
                              bool itemPerTriangle) {
  if (range.triangleCount == 0) return;
  const GlMeshSlot& slot = pipeline_.buffers().slotOf(range.object);
  // A range's draw numbers its triangles by their global index.
  const std::int64_t global = static_cast<std::int64_t>(slot.firstTriangle) + range.firstTriangle;
  FlagDraw draw;
  if (role == DrawRole::Test) {
    draw.itemPerTriangle = itemPerTriangle;
    draw.itemBase = static_cast<std::int32_t>(itemPerTriangle ? item - global : item);
  }
  pipeline_.setRole(role);
  pipeline_.setObject(range.object);
  pipeline_.setLocalIdentity();
  pipeline_.setFlagDraw(draw);
  pipeline_.draw(slot, range.firstTriangle, range.triangleCount);
  countDraw(range.triangleCount);
}

bool GlFlagBackend::gatherList(ObjectId object, std::span<const std::uint32_t> triangles) {
  const GlMeshSlot& slot = pipeline_.buffers().slotOf(object);
  listScratch_.clear();
  bool consecutive = true;
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const std::uint32_t t = triangles[i];
    if (t >= slot.triangleCount)
      throw RunError("triangle " + std::to_string(t) + " is outside object " +
                     std::to_string(object) + "'s " + std::to_string(slot.triangleCount));
    consecutive = consecutive && t == triangles[0] + i;
    listScratch_.push_back(slot.firstTriangle + t);
  }
  return consecutive;
}

void GlFlagBackend::drawList(ObjectId object, std::span<const std::uint32_t> triangles,
                             bool consecutive, DrawRole role, std::uint32_t item) {
  if (consecutive) {
    drawRange({object, triangles[0], static_cast<std::uint32_t>(triangles.size())}, role, item,
              true);
    return;
  }
  const std::uint32_t first = listedTriangles_.append(listScratch_.data(), listScratch_.size());
  FlagDraw draw;
  draw.listed = true;
  if (role == DrawRole::Test) {
    draw.itemPerTriangle = true;
    // Triangle k of the draw is list entry k.
    draw.itemBase = static_cast<std::int32_t>(static_cast<std::int64_t>(item) - first);
  }
  pipeline_.setRole(role);
  pipeline_.setObject(object);
  pipeline_.setLocalIdentity();
  pipeline_.setFlagDraw(draw);
  pipeline_.drawNumbered(first, static_cast<std::uint32_t>(listScratch_.size()));
  countDraw(listScratch_.size());
}

void GlFlagBackend::drawBox(ObjectId object, const OrientedBox& box, DrawRole role,
                            std::uint32_t item) {
  FlagDraw draw;
  if (role == DrawRole::Test) draw.itemBase = static_cast<std::int32_t>(item);
  pipeline_.setRole(role);
  pipeline_.setObject(object);
  pipeline_.setLocal(boxMatrix(box));
  pipeline_.setFlagDraw(draw);
  const GlMeshSlot& cube = pipeline_.buffers().cube();
  pipeline_.draw(cube, 0, cube.triangleCount);
  countDraw(cube.triangleCount);
}

void GlFlagBackend::drawBoxes(ObjectId object, std::span<const OrientedBox> boxes, DrawRole role,
                              std::uint32_t item) {
  if (boxes.size() == 1) {
    drawBox(object, boxes[0], role, item);
    return;
  }
  boxScratch_.clear();
  for (const OrientedBox& box : boxes) {
    const Eigen::Matrix4f m = boxMatrix(box);
    boxScratch_.insert(boxScratch_.end(), m.data(), m.data() + kFloatsPerMatrix);
  }
  FlagDraw draw;
  draw.boxBase = static_cast<std::int32_t>(boxMatrices_.append(boxScratch_.data(), boxes.size()));
  if (role == DrawRole::Test) draw.itemBase = static_cast<std::int32_t>(item);
  pipeline_.setRole(role);
  pipeline_.setObject(object);
  pipeline_.setFlagDraw(draw);
  const GlMeshSlot& cube = pipeline_.buffers().cube();
  pipeline_.drawInstances(cube, static_cast<std::uint32_t>(boxes.size()));
  countDraw(static_cast<std::uint64_t>(cube.triangleCount) * boxes.size());
}

void GlFlagBackend::PassBatch::clear() {
  segments.clear();
  triangles.clear();
  listed.clear();
  boxes.clear();
  triangleCount = 0;
}

void GlFlagBackend::addRun(PassBatch& batch, ObjectId object, std::uint32_t first,
                           std::uint32_t count, std::uint32_t item, bool itemPerTriangle) {
  constexpr auto kSegment = static_cast<std::uint32_t>(kPassSegmentTriangles);
  for (std::uint32_t done = 0; done < count; done += kSegment) {
    const std::uint32_t n = std::min(kSegment, count - done);
    batch.segments.insert(batch.segments.end(),
                          {first + done, object, item + (itemPerTriangle ? done : 0),
                           itemPerTriangle ? kPassPerTriangleBit : 0u});
    batch.triangles.push_back(static_cast<std::uint8_t>(n));
  }
  batch.triangleCount += count;
}

void GlFlagBackend::addListed(PassBatch& batch, ObjectId object, std::uint32_t item) {
  constexpr auto kSegment = static_cast<std::uint32_t>(kPassSegmentTriangles);
  const auto base = static_cast<std::uint32_t>(batch.listed.size());
  const auto count = static_cast<std::uint32_t>(listScratch_.size());
  batch.listed.insert(batch.listed.end(), listScratch_.begin(), listScratch_.end());
  for (std::uint32_t done = 0; done < count; done += kSegment) {
    const std::uint32_t n = std::min(kSegment, count - done);
    batch.segments.insert(batch.segments.end(), {base + done, object, item + done,
                                                 kPassPerTriangleBit | kPassListedBit});
    batch.triangles.push_back(static_cast<std::uint8_t>(n));
  }
  batch.triangleCount += count;
}

void GlFlagBackend::addBox(PassBatch& batch, ObjectId object, const OrientedBox& box,
                           std::uint32_t item) {
  const GlMeshSlot& cube = pipeline_.buffers().cube();
  const auto index = static_cast<std::uint32_t>(batch.boxes.size() / kFloatsPerMatrix);
  const Eigen::Matrix4f m = boxMatrix(box);
  batch.boxes.insert(batch.boxes.end(), m.data(), m.data() + kFloatsPerMatrix);
  batch.segments.insert(batch.segments.end(),
                        {cube.firstTriangle, object, item, (index + 1) << kPassBoxShift});
  batch.triangles.push_back(static_cast<std::uint8_t>(cube.triangleCount));
  batch.triangleCount += cube.triangleCount;
}

GlFlagBackend::PassBatch& GlFlagBackend::passWrites() {
  if (testedInPass_) throw RunError("a write after a test in an order-independent pass");
  return passWrites_;
}

GlFlagBackend::PassBatch& GlFlagBackend::passTests() {
  if (!testedInPass_) {
    drawPassWrites();
    testedInPass_ = true;
  }
  return passTests_;
}

GlVisibilityPipeline::PassBases GlFlagBackend::uploadPassBatch(const PassBatch& batch) {
  GlVisibilityPipeline::PassBases bases;
  bases.segment = static_cast<std::int32_t>(
      passSegments_.append(batch.segments.data(), batch.segmentCount()));
  if (!batch.listed.empty())
    bases.listed = static_cast<std::int32_t>(
        listedTriangles_.append(batch.listed.data(), batch.listed.size()));
  if (!batch.boxes.empty())
    bases.box = static_cast<std::int32_t>(
        boxMatrices_.append(batch.boxes.data(), batch.boxes.size() / kFloatsPerMatrix));
  return bases;
}

void GlFlagBackend::drawPassBatch(const PassBatch& batch, PassStage stage,
                                  const GlVisibilityPipeline::PassBases& bases) {
  pipeline_.drawPass(stage, bases, batch.triangles);
  countDraw(batch.triangleCount);
}

void GlFlagBackend::drawPassWrites() {
  if (writesDrawn_ == passWrites_.segmentCount()) return;
  // d2 depends on every write's id1: later writes redraw them all.
  if (writesDrawn_ > 0) pipeline_.clearPassBuffers();
  const auto bases = uploadPassBatch(passWrites_);
  drawPassBatch(passWrites_, PassStage::Nearest, bases);
  drawPassBatch(passWrites_, PassStage::Others, bases);
  writesDrawn_ = passWrites_.segmentCount();
}

void GlFlagBackend::drawPassTests() {
  drawPassWrites();
  if (passTests_.segmentCount() == 0) return;
  drawPassBatch(passTests_, PassStage::Test, uploadPassBatch(passTests_));
  passTests_.clear();
}

QueryIndex GlFlagBackend::queryRange(const MeshRange& range) {
  pipeline_.checkRange(range);
  const std::uint32_t item = flags_.reserve(1);
  if (orderIndependent_) {
    const GlMeshSlot& slot = pipeline_.buffers().slotOf(range.object);
    addRun(passTests(), range.object, slot.firstTriangle + range.firstTriangle,
           range.triangleCount, item, false);
    ++counters_.queries;
    return item;
  }
  drawRange(range, DrawRole::Test, item, false);
  ++counters_.queries;
  return item;
}

QueryIndex GlFlagBackend::queryBox(ObjectId object, const OrientedBox& localBox) {
  pipeline_.checkedSlot(object);
  const std::uint32_t item = flags_.reserve(1);
  if (orderIndependent_)
    addBox(passTests(), object, localBox, item);
  else
    drawBox(object, localBox, DrawRole::Test, item);
  ++counters_.queries;
  return item;
}

QueryIndex GlFlagBackend::queryTriangles(const MeshRange& range) {
  pipeline_.checkRange(range);
  if (range.triangleCount == 0) return kNoQuery;
  const std::uint32_t item = flags_.reserve(range.triangleCount);
  if (orderIndependent_)
    addRun(passTests(), range.object,
           pipeline_.buffers().slotOf(range.object).firstTriangle + range.firstTriangle,
           range.triangleCount, item, true);
  else
    drawRange(range, DrawRole::Test, item, true);
  counters_.queries += range.triangleCount;
  return item;
}

QueryIndex GlFlagBackend::queryTriangles(ObjectId object,
                                         std::span<const std::uint32_t> triangles) {
  pipeline_.checkedSlot(object);
  if (triangles.empty()) return kNoQuery;
  // Checked before any item is taken, so that a bad list leaves the round as it was.
  const bool consecutive = gatherList(object, triangles);
  const std::uint32_t item = flags_.reserve(triangles.size());
  if (orderIndependent_ && consecutive)
    addRun(passTests(), object, listScratch_[0], static_cast<std::uint32_t>(listScratch_.size()),
           item, true);
  else if (orderIndependent_)
    addListed(passTests(), object, item);
  else
    drawList(object, triangles, consecutive, DrawRole::Test, item);
  counters_.queries += triangles.size();
  return item;
}

QueryIndex GlFlagBackend::queryBoxes(ObjectId object, std::span<const OrientedBox> localBoxes) {
  pipeline_.checkedSlot(object);
  if (localBoxes.empty()) return kNoQuery;
  const std::uint32_t item = flags_.reserve(localBoxes.size());
  if (orderIndependent_) {
    PassBatch& tests = passTests();
    for (std::size_t i = 0; i < localBoxes.size(); ++i)
      addBox(tests, object, localBoxes[i], item + static_cast<std::uint32_t>(i));
  } else {
    drawBoxes(object, localBoxes, DrawRole::Test, item);
  }
  counters_.queries += localBoxes.size();
  return item;
}

void GlFlagBackend::writeRange(const MeshRange& range) {
  pipeline_.checkRange(range);
  if (orderIndependent_) {
    PassBatch& writes = passWrites();
    addRun(writes, range.object,
           pipeline_.buffers().slotOf(range.object).firstTriangle + range.firstTriangle,
           range.triangleCount, 0, false);
    return;
  }
  drawRange(range, DrawRole::Write, 0, false);
}

void GlFlagBackend::writeTriangles(ObjectId object, std::span<const std::uint32_t> triangles) {
  pipeline_.checkedSlot(object);
  if (orderIndependent_) {
    PassBatch& writes = passWrites();
    if (gatherList(object, triangles) && !triangles.empty())
      addRun(writes, object, listScratch_[0], static_cast<std::uint32_t>(listScratch_.size()), 0,
             false);
    else
      addListed(writes, object, 0);
    return;
  }
  if (triangles.empty()) return;
  drawList(object, triangles, gatherList(object, triangles), DrawRole::Write, 0);
}

void GlFlagBackend::writeBox(ObjectId object, const OrientedBox& localBox) {
  pipeline_.checkedSlot(object);
  if (orderIndependent_) {
    addBox(passWrites(), object, localBox, 0);
    return;
  }
  drawBox(object, localBox, DrawRole::Write, 0);
}

void GlFlagBackend::writeBoxes(ObjectId object, std::span<const OrientedBox> localBoxes) {
  pipeline_.checkedSlot(object);
  if (orderIndependent_) {
    PassBatch& writes = passWrites();
    for (const OrientedBox& box : localBoxes) addBox(writes, object, box, 0);
    return;
  }
  if (localBoxes.empty()) return;
  drawBoxes(object, localBoxes, DrawRole::Write, 0);
}

void GlFlagBackend::fetchAnswers(std::vector<std::uint8_t>& fullyVisible) {
  // Writes are drawn by a fetch too, so that tests after it in the pass read them.
  if (orderIndependent_) drawPassTests();
  if (flags_.used() > 0) ++counters_.fetches;
  const auto start = std::chrono::steady_clock::now();
  flags_.fetch(fullyVisible);
  counters_.fetchWaitNs += static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start)
          .count());
  counters_.gpuDrawNs += pipeline_.collectDrawNs();
  listedTriangles_.rewind();
  boxMatrices_.rewind();
  passSegments_.rewind();
}

}  // namespace cdb
