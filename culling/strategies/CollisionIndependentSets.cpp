#include "culling/strategies/CollisionIndependentSets.h"

#include "culling/ViewAxis.h"

// Algorithm 3.2's decisions, and why the sets it builds are safe, are in CisConstruction; this
// draws whole objects for it, pass 2 testing only the objects the algorithm asks about.

namespace cdb {

CollisionIndependentSets::CollisionIndependentSets(const DetectorOptions& options, CisOptions cis)
    : options_(options), config_(cis) {}

void CollisionIndependentSets::attach(const SceneGeometry& scene, VisibilityBackend& backend) {
  scene_ = &scene;
  backend_ = &backend;
  bounds_.attach(scene);
  allObjects_.resize(scene.objectCount());
  for (std::size_t i = 0; i < allObjects_.size(); ++i) allObjects_[i] = static_cast<ObjectId>(i);
}

CullingResult CollisionIndependentSets::cull(const FrameInput& frame) {
  const VisibilityCounters before = backend_->counters();
  CullingResult result;
  stats_ = {};
  const std::size_t n = allObjects_.size();
  if (n < 2) return result;  // an object alone collides with nothing

  backend_->setPoses(frame.poses);
  bounds_.update(frame.poses);
  stats_.axis = config_.axis.value_or(axisOfLargestSpread(
      n, [&](std::size_t slot) { return bounds_[allObjects_[slot]].center(); }));
  SortedIntervals& sorted = sorted_[stats_.axis];
  stats_.sortExchanges = sorted.update(allObjects_, bounds_, Eigen::Vector3d::Unit(stats_.axis));

  cis_.reset(sorted);
  const auto order = cis_.passOneOrder();
  const ViewSpec view{Eigen::Vector3d::Unit(stats_.axis), bounds_.unionOf(allObjects_),
                      options_.resolution};

  // Pass 1: draws do not depend on answers, so every query is issued before the one fetch.
  backend_->beginPass(view, DepthUse::SharedFirst);
  for (std::uint32_t slot : order) {
    backend_->queryRange(wholeMesh(*scene_, allObjects_[slot]));
    backend_->writeRange(wholeMesh(*scene_, allObjects_[slot]));
  }
  backend_->fetchResults(visible_);
  bySlot_.assign(n, 0);
  for (std::size_t k = 0; k < order.size(); ++k) bySlot_[order[k]] = visible_[k];
  cis_.firstPass(bySlot_);
  stats_.separatingSurfaces = cis_.separatingSurfaces();

  // Pass 2: which objects are tested depends only on pass 1, so again one fetch.
  ViewSpec opposite = view;
  opposite.direction = -view.direction;
  backend_->beginPass(opposite, DepthUse::SharedSecond);
  std::vector<std::uint32_t> tested;
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    if (cis_.testedInSecondPass(*it)) {
      backend_->queryRange(wholeMesh(*scene_, allObjects_[*it]));
      tested.push_back(*it);
    }
    backend_->writeRange(wholeMesh(*scene_, allObjects_[*it]));
  }
  backend_->fetchResults(visible_);
  for (std::size_t k = 0; k < tested.size(); ++k) bySlot_[tested[k]] = visible_[k];
  cis_.secondPass(bySlot_);
  stats_.dropped = cis_.dropped();

  for (const auto& members : cis_.sets()) {
    if (members.size() < 2) {
      ++stats_.singletons;
      continue;
    }
    PotentiallyCollidingSet out;
    for (std::uint32_t slot : members) {
      const ObjectId o = allObjects_[slot];
      out.members.push_back({o, {}});
      result.counters.pcsTriangles += scene_->meshOf(o).triangleCount();
    }
    result.counters.pcsSize += members.size();
    result.sets.push_back(std::move(out));
  }
  result.counters.sets = result.sets.size();
  result.counters.visibility = backend_->counters() - before;
  return result;
}

}  // namespace cdb
