#include "culling/strategies/DepthSortedCulling.h"

#include "culling/TwoPassPruning.h"

namespace cdb {


DepthSortedCulling::DepthSortedCulling(const DetectorOptions& options) : options_(options) {}

void DepthSortedCulling::attach(const SceneGeometry& scene, VisibilityBackend& backend) {
  scene_ = &scene;
  backend_ = &backend;
  bounds_.attach(scene);
  allObjects_.resize(scene.objectCount());
  for (std::size_t i = 0; i < allObjects_.size(); ++i) allObjects_[i] = static_cast<ObjectId>(i);
  inSet_.assign(scene.objectCount(), 0);
}

ViewSpec DepthSortedCulling::viewAlong(int axis, const Aabb& bounds) const {
  return {Eigen::Vector3d::Unit(axis), bounds, options_.resolution};
}

void DepthSortedCulling::farToNear(int axis, std::vector<ObjectId>& order) const {
  order.clear();
  const auto list = sorted_[axis].endpoints();
  for (auto it = list.rbegin(); it != list.rend(); ++it)
    if (!it->isMax && inSet_[it->object]) order.push_back(it->object);
}

void DepthSortedCulling::pruneObjects(std::vector<ObjectId>& pcs, int axis) {
  if (pcs.size() < 2) {
    pcs.clear();
    return;
  }
  for (ObjectId o : pcs) inSet_[o] = 1;
  std::vector<ObjectId> order;
  farToNear(axis, order);
  for (ObjectId o : pcs) inSet_[o] = 0;

  pcs = pruneObjectsTwoPass(*backend_, *scene_, order,
                            PassPair::shared(viewAlong(axis, bounds_.unionOf(pcs))), visible_);
}

void DepthSortedCulling::pruneTriangles(std::vector<SetMember>& members, int axis) {
  if (members.size() < 2) {
    members.clear();
    return;
  }
  std::vector<ObjectId> objects;
  for (const auto& m : members) {
    objects.push_back(m.object);
    inSet_[m.object] = 1;
  }
  std::vector<ObjectId> order;
  farToNear(axis, order);
  for (ObjectId o : objects) inSet_[o] = 0;
  // Members in pass-1 order: look each up by object id.
  std::vector<SetMember> ordered;
  ordered.reserve(members.size());
  {
    std::vector<std::size_t> slotOf(scene_->objectCount());
    for (std::size_t i = 0; i < members.size(); ++i) slotOf[members[i].object] = i;
    for (ObjectId o : order) ordered.push_back(std::move(members[slotOf[o]]));
  }

  members = pruneTrianglesTwoPass(*backend_, *scene_, std::move(ordered),
                                  PassPair::shared(viewAlong(axis, bounds_.unionOf(objects))), visible_);
}

CullingResult DepthSortedCulling::cull(const FrameInput& frame) {
  const VisibilityCounters before = backend_->counters();
  backend_->setPoses(frame.poses);
  bounds_.update(frame.poses);
  exchanges_ = 0;
  for (int axis = 0; axis < 3; ++axis)
    exchanges_ += sorted_[axis].update(allObjects_, bounds_, Eigen::Vector3d::Unit(axis));

  std::vector<ObjectId> pcs = allObjects_;
  for (int axis = 0; axis < 3; ++axis) pruneObjects(pcs, axis);

  std::vector<SetMember> members = withAllTriangles(pcs);
  for (int axis = 0; axis < 3; ++axis) pruneTriangles(members, axis);

  return singleSetResult(*scene_, std::move(members), backend_->counters() - before);
}

}  // namespace cdb
