#include "culling/visibility/GlOcclusionQueryBackend.h"

#include <chrono>
#include <string>

#include "core/Errors.h"
#include "culling/visibility/VisibilityBackendRegistry.h"
#include "render/HeadlessGlContext.h"

namespace cdb {

GlOcclusionQueryBackend::GlOcclusionQueryBackend(HeadlessGlContext& context,
                                                 const VisibilityOptions& options)
    : context_(&context), pipeline_(context) {
  setOptions(options);
}

std::string GlOcclusionQueryBackend::renderer() const { return context_->info().glRenderer; }

void GlOcclusionQueryBackend::setOptions(const VisibilityOptions& options) {
  pipeline_.setConservative(options.conservative);
  pipeline_.setRawDepthOffset(options.rawDepthOffset);
  pipeline_.timeDraws(options.timeGpu);
}

void GlOcclusionQueryBackend::attachScene(const SceneGeometry& scene) { pipeline_.attach(scene); }

void GlOcclusionQueryBackend::setPoses(std::span<const Pose> poses) {
  pipeline_.uploadPoses(poses);
}

void GlOcclusionQueryBackend::beginPass(const ViewSpec& view, DepthUse depth) {
  // An occlusion query counts the samples that pass the depth test of one buffer; the pass would
  // need a second depth and a per-pixel choice between them, which gl-flags draws.
  if (depth == DepthUse::OrderIndependent) {
    std::string offered;
    const auto& registry = VisibilityBackendRegistry::builtin();
    for (const auto& name : registry.names())
      if (registry.traits(name).orderIndependent) offered += (offered.empty() ? "" : ", ") + name;
    throw InputError(
        "the gl-queries backend offers no order-independent pass (cullide_oi needs one); "
        "backends that do: " + offered);
  }
  const DepthPassSetup setup = pipeline_.beginCheckedPass(view, depth);
  ++counters_.passes;
  if (setup.clear) ++counters_.depthClears;
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
  pipeline_.checkRange(range);
  const QueryIndex index = pipeline_.beginQuery();
  drawRange(range, DrawRole::Test);
  pipeline_.endQuery();
  ++counters_.queries;
  return index;
}

QueryIndex GlOcclusionQueryBackend::queryBox(ObjectId object, const OrientedBox& localBox) {
  pipeline_.checkedSlot(object);
  const QueryIndex index = pipeline_.beginQuery();
  drawBox(object, localBox, DrawRole::Test);
  pipeline_.endQuery();
  ++counters_.queries;
  return index;
}

void GlOcclusionQueryBackend::writeRange(const MeshRange& range) {
  pipeline_.checkRange(range);
  drawRange(range, DrawRole::Write);
}

void GlOcclusionQueryBackend::writeBox(ObjectId object, const OrientedBox& localBox) {
  pipeline_.checkedSlot(object);
  drawBox(object, localBox, DrawRole::Write);
}

void GlOcclusionQueryBackend::writeTriangles(ObjectId object,
                                             std::span<const std::uint32_t> triangles) {
  const GlMeshSlot& slot = pipeline_.checkedSlot(object);
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

void GlOcclusionQueryBackend::fetchAnswers(std::vector<std::uint8_t>& fullyVisible) {
  if (pipeline_.pendingQueries() > 0) ++counters_.fetches;
  const auto start = std::chrono::steady_clock::now();
  pipeline_.fetch(fullyVisible);
  counters_.fetchWaitNs += static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start)
          .count());
  counters_.gpuDrawNs += pipeline_.collectDrawNs();
}

}  // namespace cdb
