#include "culling/strategies/OrderIndependentCullide.h"

#include <string>

#include "core/Errors.h"
#include "culling/TwoPassPruning.h"

namespace cdb {

OrderIndependentCullide::OrderIndependentCullide(const DetectorOptions& options)
    : options_(options) {}

void OrderIndependentCullide::attach(const SceneGeometry& scene, VisibilityBackend& backend) {
  if (!backend.supportsOrderIndependent())
    throw InputError("cullide_oi needs order-independent passes, which the " +
                     std::string(backend.name()) + " backend does not offer");
  scene_ = &scene;
  backend_ = &backend;
  bounds_.attach(scene);
}

// Every object written, then every object tested against the others' writes: fully visible with
// respect to all the others means touching none of them (CULLIDE's two passes at once).
void OrderIndependentCullide::pruneObjects(std::vector<ObjectId>& pcs,
                                           const Eigen::Vector3d& axis) {
  if (pcs.size() < 2) {
    pcs.clear();
    return;
  }
  backend_->beginPass({axis, bounds_.unionOf(pcs), options_.resolution},
                      DepthUse::OrderIndependent);
  for (ObjectId o : pcs) backend_->writeRange(wholeMesh(*scene_, o));
  for (ObjectId o : pcs) (void)backend_->queryRange(wholeMesh(*scene_, o));
  backend_->fetchResults(visible_);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < pcs.size(); ++i)
    if (!visible_[i]) pcs[kept++] = pcs[i];
  pcs.resize(kept);
}

// The same per triangle of the objects left: each member written (whole, or its triangles left),
// then each triangle tested; an object's own triangles never occlude it.
void OrderIndependentCullide::pruneTriangles(std::vector<SetMember>& members,
                                             const Eigen::Vector3d& axis) {
  if (members.size() < 2) {
    members.clear();
    return;
  }
  std::vector<ObjectId> objects;
  for (const auto& m : members) objects.push_back(m.object);
  backend_->beginPass({axis, bounds_.unionOf(objects), options_.resolution},
                      DepthUse::OrderIndependent);
  for (const auto& m : members) writeMemberTriangles(*backend_, *scene_, m);
  for (const auto& m : members) (void)queryMemberTriangles(*backend_, *scene_, m);
  backend_->fetchResults(visible_);
  std::vector<SetMember> kept;
  std::size_t piece = 0;
  const auto occluded = [&](std::size_t i) { return !visible_[i]; };
  for (auto& m : members) piece += keepTriangles(*scene_, std::move(m), piece, occluded, kept);
  members = std::move(kept);
}

CullingResult OrderIndependentCullide::cull(const FrameInput& frame) {
  const VisibilityCounters before = backend_->counters();
  backend_->setPoses(frame.poses);
  bounds_.update(frame.poses);

  std::vector<SetMember> members = pruneCullideLevels(
      *scene_,
      [this](std::vector<ObjectId>& pcs, const Eigen::Vector3d& axis) { pruneObjects(pcs, axis); },
      [this](std::vector<SetMember>& m, const Eigen::Vector3d& axis) { pruneTriangles(m, axis); });
  return singleSetResult(*scene_, std::move(members), backend_->counters() - before);
}

}  // namespace cdb
