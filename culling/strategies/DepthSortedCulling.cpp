#include "culling/strategies/DepthSortedCulling.h"

#include <algorithm>

namespace cdb {

namespace {
MeshRange wholeMesh(const SceneGeometry& scene, ObjectId o) {
  return {o, 0, static_cast<std::uint32_t>(scene.meshOf(o).triangleCount())};
}
}  // namespace

DepthSortedCulling::DepthSortedCulling(const StrategyOptions& options) : options_(options) {}

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

  const ViewSpec view = viewAlong(axis, bounds_.unionOf(pcs));
  backend_->beginPass(view, DepthUse::SharedFirst);
  for (ObjectId o : order) {
    backend_->queryRange(wholeMesh(*scene_, o));
    backend_->writeRange(wholeMesh(*scene_, o));
  }
  ViewSpec opposite = view;
  opposite.direction = -view.direction;
  backend_->beginPass(opposite, DepthUse::SharedSecond);
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    backend_->queryRange(wholeMesh(*scene_, *it));
    backend_->writeRange(wholeMesh(*scene_, *it));
  }
  backend_->fetchResults(visible_);

  const std::size_t n = order.size();
  pcs.clear();
  for (std::size_t i = 0; i < n; ++i)
    if (!(visible_[i] && visible_[2 * n - 1 - i])) pcs.push_back(order[i]);
}

// The same two passes with one query per triangle; an object's own triangles are all tested
// before it is drawn, so an object never occludes itself.
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

  auto drawMember = [&](const SetMember& m) {
    for (std::uint32_t t : m.triangles) backend_->queryRange({m.object, t, 1});
    if (m.triangles.size() == scene_->meshOf(m.object).triangleCount())
      backend_->writeRange(wholeMesh(*scene_, m.object));
    else
      backend_->writeTriangles(m.object, m.triangles);
  };
  const ViewSpec view = viewAlong(axis, bounds_.unionOf(objects));
  backend_->beginPass(view, DepthUse::SharedFirst);
  for (const auto& m : ordered) drawMember(m);
  ViewSpec opposite = view;
  opposite.direction = -view.direction;
  backend_->beginPass(opposite, DepthUse::SharedSecond);
  for (auto it = ordered.rbegin(); it != ordered.rend(); ++it) drawMember(*it);
  backend_->fetchResults(visible_);

  std::size_t total = 0;
  for (const auto& m : ordered) total += m.triangles.size();
  members.clear();
  std::size_t first1 = 0;
  std::size_t end2 = 2 * total;  // pass 2 runs members in reverse, so member i ends where i-1 began
  for (auto& m : ordered) {
    const std::size_t count = m.triangles.size();
    const std::size_t first2 = end2 - count;
    SetMember out{m.object, {}};
    for (std::size_t k = 0; k < count; ++k)
      if (!(visible_[first1 + k] && visible_[first2 + k])) out.triangles.push_back(m.triangles[k]);
    first1 += count;
    end2 = first2;
    if (!out.triangles.empty()) members.push_back(std::move(out));
  }
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

  std::vector<SetMember> members;
  for (ObjectId o : pcs) {
    SetMember m{o, {}};
    m.triangles.resize(scene_->meshOf(o).triangleCount());
    for (std::uint32_t t = 0; t < m.triangles.size(); ++t) m.triangles[t] = t;
    members.push_back(std::move(m));
  }
  for (int axis = 0; axis < 3; ++axis) pruneTriangles(members, axis);

  CullingResult result;
  result.counters.pcsSize = members.size();
  for (auto& m : members) {
    result.counters.pcsTriangles += m.triangles.size();
    if (m.triangles.size() == scene_->meshOf(m.object).triangleCount()) m.triangles.clear();
  }
  if (!members.empty()) {
    result.sets.push_back({std::move(members)});
    result.counters.sets = 1;
  }
  result.counters.visibility = backend_->counters() - before;
  return result;
}

}  // namespace cdb
