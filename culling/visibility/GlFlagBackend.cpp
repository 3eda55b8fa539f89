#include "culling/visibility/GlFlagBackend.h"

#include <string>

#include "core/Errors.h"
#include "culling/visibility/FlagShaders.h"
#include "render/HeadlessGlContext.h"

namespace cdb {

namespace {
constexpr std::size_t kFloatsPerMatrix = 16;
}  // namespace

GlFlagBackend::GlFlagBackend(HeadlessGlContext& context, const VisibilityOptions& options)
    : context_(&context),
      pipeline_(context, PipelinePrograms::Flags),
      flags_(kItemFlagBinding),
      listedTriangles_(kListedTriangleBinding, sizeof(std::uint32_t)),
      boxMatrices_(kBoxMatrixBinding, kFloatsPerMatrix * sizeof(float)) {
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
  pipeline_.setConservative(options.conservative);
  pipeline_.setRawDepthOffset(options.rawDepthOffset);
}

void GlFlagBackend::attachScene(const SceneGeometry& scene) { pipeline_.attach(scene); }

void GlFlagBackend::setPoses(std::span<const Pose> poses) { pipeline_.uploadPoses(poses); }

void GlFlagBackend::beginPass(const ViewSpec& view, DepthUse depth) {
  const DepthPassSetup setup = pipeline_.beginCheckedPass(view, depth);
  // Another pipeline on the context may have bound its own buffers since the last pass.
  flags_.bind();
  listedTriangles_.bind();
  boxMatrices_.bind();
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

QueryIndex GlFlagBackend::queryRange(const MeshRange& range) {
  pipeline_.checkRange(range);
  const std::uint32_t item = flags_.reserve(1);
  drawRange(range, DrawRole::Test, item, false);
  ++counters_.queries;
  return item;
}

QueryIndex GlFlagBackend::queryBox(ObjectId object, const OrientedBox& localBox) {
  pipeline_.checkedSlot(object);
  const std::uint32_t item = flags_.reserve(1);
  drawBox(object, localBox, DrawRole::Test, item);
  ++counters_.queries;
  return item;
}

QueryIndex GlFlagBackend::queryTriangles(const MeshRange& range) {
  pipeline_.checkRange(range);
  if (range.triangleCount == 0) return kNoQuery;
  const std::uint32_t item = flags_.reserve(range.triangleCount);
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
  drawList(object, triangles, consecutive, DrawRole::Test, item);
  counters_.queries += triangles.size();
  return item;
}

QueryIndex GlFlagBackend::queryBoxes(ObjectId object, std::span<const OrientedBox> localBoxes) {
  pipeline_.checkedSlot(object);
  if (localBoxes.empty()) return kNoQuery;
  const std::uint32_t item = flags_.reserve(localBoxes.size());
  drawBoxes(object, localBoxes, DrawRole::Test, item);
  counters_.queries += localBoxes.size();
  return item;
}

void GlFlagBackend::writeRange(const MeshRange& range) {
  pipeline_.checkRange(range);
  drawRange(range, DrawRole::Write, 0, false);
}

void GlFlagBackend::writeTriangles(ObjectId object, std::span<const std::uint32_t> triangles) {
  pipeline_.checkedSlot(object);
  if (triangles.empty()) return;
  drawList(object, triangles, gatherList(object, triangles), DrawRole::Write, 0);
}

void GlFlagBackend::writeBox(ObjectId object, const OrientedBox& localBox) {
  pipeline_.checkedSlot(object);
  drawBox(object, localBox, DrawRole::Write, 0);
}

void GlFlagBackend::writeBoxes(ObjectId object, std::span<const OrientedBox> localBoxes) {
  pipeline_.checkedSlot(object);
  if (localBoxes.empty()) return;
  drawBoxes(object, localBoxes, DrawRole::Write, 0);
}

void GlFlagBackend::fetchResults(std::vector<std::uint8_t>& fullyVisible) {
  if (flags_.used() > 0) ++counters_.fetches;
  flags_.fetch(fullyVisible);
  listedTriangles_.rewind();
  boxMatrices_.rewind();
}

}  // namespace cdb
