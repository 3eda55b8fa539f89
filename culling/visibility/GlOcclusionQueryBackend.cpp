#include "culling/visibility/GlOcclusionQueryBackend.h"

#include <string>

#include "core/Errors.h"
#include "render/HeadlessGlContext.h"

namespace cdb {

Eigen::Matrix4f boxMatrix(const OrientedBox& box) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = box.axes * box.halfExtents.asDiagonal();
  m.topRightCorner<3, 1>() = box.center;
  return m.cast<float>();
}

GlOcclusionQueryBackend::GlOcclusionQueryBackend(HeadlessGlContext& context,
                                                 const VisibilityOptions& options)
    : context_(&context), pipeline_(context) {
  setOptions(options);
}

std::string GlOcclusionQueryBackend::renderer() const { return context_->info().glRenderer; }

void GlOcclusionQueryBackend::setOptions(const VisibilityOptions& options) {
  options_ = options;
  pipeline_.setConservative(options.conservative);
  pipeline_.setRawDepthOffset(options.rawDepthOffset);
}

void GlOcclusionQueryBackend::attachScene(const SceneGeometry& scene) {
  pipeline_.attach(scene);
  lastResolution_ = 0;
}

void GlOcclusionQueryBackend::setPoses(std::span<const Pose> poses) {
  pipeline_.uploadPoses(poses);
}

void GlOcclusionQueryBackend::beginPass(const ViewSpec& view, DepthUse depth) {
  if (depth == DepthUse::SharedSecond &&
      (lastDepth_ != DepthUse::SharedFirst || lastResolution_ != view.resolution))
    throw RunError("a SharedSecond pass must follow a SharedFirst pass of the same resolution");
  const DepthPassSetup setup = makeDepthPassSetup(view, depth);
  pipeline_.beginPass(setup);
  lastDepth_ = depth;
  lastResolution_ = view.resolution;
  ++counters_.passes;
  if (setup.clear) ++counters_.depthClears;
}

const GlMeshSlot& GlOcclusionQueryBackend::checkedSlot(ObjectId object) const {
  if (object >= pipeline_.buffers().objectCount())
    throw RunError("object " + std::to_string(object) + " is not in the attached scene of " +
                   std::to_string(pipeline_.buffers().objectCount()) + " objects");
  if (!pipeline_.inPass()) throw RunError("a visibility draw was issued outside a pass");
  return pipeline_.buffers().slotOf(object);
}

void GlOcclusionQueryBackend::checkRange(const MeshRange& range) const {
  const GlMeshSlot& slot = checkedSlot(range.object);
  if (range.firstTriangle > slot.triangleCount ||
      range.triangleCount > slot.triangleCount - range.firstTriangle)
    throw RunError("triangles [" + std::to_string(range.firstTriangle) + ", +" +
                   std::to_string(range.triangleCount) + ") are outside object " +
                   std::to_string(range.object) + "'s " + std::to_string(slot.triangleCount));
}

void GlOcclusionQueryBackend::drawRange(const MeshRange& range, DrawRole role) {
  pipeline_.setRole(role);
  pipeline_.setObject(range.object);
  pipeline_.setLocalIdentity();
  if (range.triangleCount == 0) return;
  pipeline_.draw(pipeline_.buffers().slotOf(range.object), range.firstTriangle,
                 range.triangleCount);
  ++counters_.draws;
  counters_.trianglesDrawn += range.triangleCount;
}

void GlOcclusionQueryBackend::drawBox(ObjectId object, const OrientedBox& box, DrawRole role) {
  pipeline_.setRole(role);
  pipeline_.setObject(object);
  pipeline_.setLocal(boxMatrix(box));
  const GlMeshSlot& cube = pipeline_.buffers().cube();
  pipeline_.draw(cube, 0, cube.triangleCount);
  ++counters_.draws;
  counters_.trianglesDrawn += cube.triangleCount;
}

QueryIndex GlOcclusionQueryBackend::queryRange(const MeshRange& range) {
  checkRange(range);
  const QueryIndex index = pipeline_.beginQuery();
  drawRange(range, DrawRole::Test);
  pipeline_.endQuery();
  ++counters_.queries;
  return index;
}

QueryIndex GlOcclusionQueryBackend::queryBox(ObjectId object, const OrientedBox& localBox) {
  checkedSlot(object);
  const QueryIndex index = pipeline_.beginQuery();
  drawBox(object, localBox, DrawRole::Test);
  pipeline_.endQuery();
  ++counters_.queries;
  return index;
}

void GlOcclusionQueryBackend::writeRange(const MeshRange& range) {
  checkRange(range);
  drawRange(range, DrawRole::Write);
}

void GlOcclusionQueryBackend::writeBox(ObjectId object, const OrientedBox& localBox) {
  checkedSlot(object);
  drawBox(object, localBox, DrawRole::Write);
}

void GlOcclusionQueryBackend::writeTriangles(ObjectId object,
                                             std::span<const std::uint32_t> triangles) {
  const GlMeshSlot& slot = checkedSlot(object);
  // Consecutive triangles become one run; all runs go in one multi-draw.
  runs_.clear();
  for (std::size_t i = 0; i < triangles.size();) {
    const std::uint32_t first = triangles[i];
    std::uint32_t count = 1;
    while (i + count < triangles.size() && triangles[i + count] == first + count) ++count;
    if (first >= slot.triangleCount || count > slot.triangleCount - first)
      throw RunError("triangle " + std::to_string(first + count - 1) + " is outside object " +
                     std::to_string(object) + "'s " + std::to_string(slot.triangleCount));
    runs_.push_back({first, count});
    i += count;
  }
  if (runs_.empty()) return;
  pipeline_.setRole(DrawRole::Write);
  pipeline_.setObject(object);
  pipeline_.setLocalIdentity();
  pipeline_.drawRuns(slot, runs_);
  ++counters_.draws;
  counters_.trianglesDrawn += triangles.size();
}

void GlOcclusionQueryBackend::fetchResults(std::vector<std::uint8_t>& fullyVisible) {
  if (pipeline_.pendingQueries() > 0) ++counters_.fetches;
  pipeline_.fetch(fullyVisible);
}

}  // namespace cdb
