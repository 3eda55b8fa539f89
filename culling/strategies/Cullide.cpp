#include "culling/strategies/Cullide.h"

#include "culling/TwoPassPruning.h"

namespace cdb {

Cullide::Cullide(const DetectorOptions& options) : options_(options) {}

void Cullide::attach(const SceneGeometry& scene, VisibilityBackend& backend) {
  scene_ = &scene;
  backend_ = &backend;
  bounds_.attach(scene);
}

// Pass 1 tests each object against those drawn before it, pass 2 (reverse order, fresh depth)
// against those after it: fully visible in both means it touches nothing else in the PCS.
void Cullide::pruneObjects(std::vector<ObjectId>& pcs, const Eigen::Vector3d& axis) {
  if (pcs.size() < 2) {
    pcs.clear();
    return;
  }
  const ViewSpec view{axis, bounds_.unionOf(pcs), options_.resolution};
  pcs = pruneObjectsTwoPass(*backend_, *scene_, pcs, PassPair::fresh(view), visible_);
}

void Cullide::pruneTriangles(std::vector<SetMember>& members, const Eigen::Vector3d& axis) {
  if (members.size() < 2) {
    members.clear();
    return;
  }
  std::vector<ObjectId> objects;
  for (const auto& m : members) objects.push_back(m.object);
  const ViewSpec view{axis, bounds_.unionOf(objects), options_.resolution};
  members = pruneTrianglesTwoPass(*backend_, *scene_, std::move(members), PassPair::fresh(view), visible_);
}

CullingResult Cullide::cull(const FrameInput& frame) {
  const VisibilityCounters before = backend_->counters();
  backend_->setPoses(frame.poses);
  bounds_.update(frame.poses);

  std::vector<SetMember> members = pruneCullideLevels(
      *scene_, [this](std::vector<ObjectId>& pcs, const Eigen::Vector3d& axis) { pruneObjects(pcs, axis); },
      [this](std::vector<SetMember>& m, const Eigen::Vector3d& axis) { pruneTriangles(m, axis); });
  return singleSetResult(*scene_, std::move(members), backend_->counters() - before);
}

}  // namespace cdb
