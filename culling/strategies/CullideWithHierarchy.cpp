#include "culling/strategies/CullideWithHierarchy.h"

#include <algorithm>
#include <span>

#include "culling/bvh/NodeDraws.h"

namespace cdb {

CullideWithHierarchy::CullideWithHierarchy(const DetectorOptions& options,
                                           CullideWithHierarchyOptions config)
    : options_(options), config_(config) {}

void CullideWithHierarchy::attach(const SceneGeometry& scene, VisibilityBackend& backend) {
  scene_ = &scene;
  backend_ = &backend;
  hierarchies_.build(scene, config_.hierarchy);
  frontier_.attach(scene, hierarchies_);
}

void CullideWithHierarchy::pruneAlong(std::vector<ObjectId>& objects, int axis,
                                      std::span<const Pose> poses) {
  if (objects.size() < 2) {
    for (ObjectId o : objects) frontier_.clear(o);
    objects.clear();
    return;
  }
  Aabb bounds;
  for (ObjectId o : objects) bounds.extend(frontier_.worldBounds(o, poses[o]));
  const ViewSpec view{Eigen::Vector3d::Unit(axis), bounds, options_.resolution};

  // Each object's node boxes, gathered once for its four draws.
  boxes_.clear();
  boxesStart_.resize(objects.size() + 1);
  for (std::size_t i = 0; i < objects.size(); ++i) {
    boxesStart_[i] = boxes_.size();
    appendNodeBoxes(frontier_, objects[i], boxes_);
  }
  boxesStart_[objects.size()] = boxes_.size();
  const auto boxesOf = [&](std::size_t i) {
    return std::span<const OrientedBox>(boxes_).subspan(boxesStart_[i],
                                                        boxesStart_[i + 1] - boxesStart_[i]);
  };
  // Pass 1 tests each node against the objects drawn before its own, pass 2 (reverse order,
  // fresh depth) against those after it; both passes are issued before the one fetch. An
  // object's nodes are all queried before any is written. Only a node fully visible in both
  // leaves, so pass 2's answers are gated by pass 1's (a backend need not test the others again).
  issueTwoPasses(
      *backend_, PassPair::fresh(view), objects.size(),
      [&](Pass, std::size_t i) { return backend_->queryBoxes(objects[i], boxesOf(i)); },
      [&](std::size_t i) { backend_->writeBoxes(objects[i], boxesOf(i)); }, queries_, visible_,
      [&](std::size_t i) { return static_cast<std::uint32_t>(boxesOf(i).size()); });

  std::size_t kept = 0;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const ObjectId o = objects[i];
    const std::size_t count = frontier_.nodes(o).size();
    keep_.resize(count);
    for (std::size_t k = 0; k < count; ++k)
      keep_[k] = !(visible_[queries_.first[i] + k] && visible_[queries_.second[i] + k]);
    if (frontier_.retain(o, keep_) > 0) objects[kept++] = o;
  }
  objects.resize(kept);
  if (objects.size() < 2) {  // an object alone collides with nothing
    for (ObjectId o : objects) frontier_.clear(o);
    objects.clear();
  }
}

CullingResult CullideWithHierarchy::cull(const FrameInput& frame) {
  const VisibilityCounters before = backend_->counters();
  backend_->setPoses(frame.poses);
  frontier_.reset();
  CullingResult result;

  std::vector<ObjectId> objects(scene_->objectCount());
  for (std::size_t i = 0; i < objects.size(); ++i) objects[i] = static_cast<ObjectId>(i);
  for (std::uint32_t level = 0; !objects.empty(); ++level) {
    LevelCounters counters{.level = level};
    const std::uint64_t queriesBefore = backend_->counters().queries;
    for (ObjectId o : objects) counters.nodesTested += frontier_.nodes(o).size();
    for (int axis = 0; axis < 3; ++axis) pruneAlong(objects, axis, frame.poses);
    for (ObjectId o : objects) counters.nodesKept += frontier_.nodes(o).size();
    counters.sets = objects.empty() ? 0 : 1;
    counters.queries = backend_->counters().queries - queriesBefore;
    result.counters.levels.push_back(counters);
    if (std::ranges::all_of(objects, [&](ObjectId o) { return frontier_.allLeaves(o); })) break;
    for (ObjectId o : objects) frontier_.expand(o);
  }

  if (!objects.empty()) {
    PotentiallyCollidingSet set;
    for (ObjectId o : objects) {
      result.counters.pcsTriangles += frontier_.triangleCount(o);
      set.members.push_back(frontier_.member(o));
    }
    result.counters.pcsSize = objects.size();
    result.counters.sets = 1;
    result.sets.push_back(std::move(set));
  }
  result.counters.visibility = backend_->counters() - before;
  return result;
}

}  // namespace cdb
