#include "culling/strategies/Cullide.h"

#include <algorithm>

namespace cdb {

namespace {
const std::array<Eigen::Vector3d, 3> kAxes = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                              Eigen::Vector3d::UnitZ()};

MeshRange wholeMesh(const SceneGeometry& scene, ObjectId o) {
  return {o, 0, static_cast<std::uint32_t>(scene.meshOf(o).triangleCount())};
}
}  // namespace

Cullide::Cullide(const StrategyOptions& options) : options_(options) {}

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
  backend_->beginPass(view, DepthUse::Fresh);
  for (ObjectId o : pcs) {
    backend_->queryRange(wholeMesh(*scene_, o));
    backend_->writeRange(wholeMesh(*scene_, o));
  }
  backend_->beginPass(view, DepthUse::Fresh);
  for (auto it = pcs.rbegin(); it != pcs.rend(); ++it) {
    backend_->queryRange(wholeMesh(*scene_, *it));
    backend_->writeRange(wholeMesh(*scene_, *it));
  }
  backend_->fetchResults(visible_);
  const std::size_t n = pcs.size();
  std::vector<ObjectId> kept;
  kept.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const bool pass1 = visible_[i];
    const bool pass2 = visible_[n + (n - 1 - i)];
    if (!(pass1 && pass2)) kept.push_back(pcs[i]);
  }
  pcs.swap(kept);
}

// The same two passes with one query per triangle; an object's own triangles are all tested
// before it is drawn, so an object never occludes itself.
void Cullide::pruneTriangles(std::vector<SetMember>& members, const Eigen::Vector3d& axis) {
  if (members.size() < 2) {
    members.clear();
    return;
  }
  std::vector<ObjectId> objects;
  for (const auto& m : members) objects.push_back(m.object);
  const ViewSpec view{axis, bounds_.unionOf(objects), options_.resolution};

  auto drawMember = [&](const SetMember& m) {
    for (std::uint32_t t : m.triangles) backend_->queryRange({m.object, t, 1});
    if (m.triangles.size() == scene_->meshOf(m.object).triangleCount())
      backend_->writeRange(wholeMesh(*scene_, m.object));
    else
      backend_->writeTriangles(m.object, m.triangles);
  };
  backend_->beginPass(view, DepthUse::Fresh);
  for (const auto& m : members) drawMember(m);
  backend_->beginPass(view, DepthUse::Fresh);
  for (auto it = members.rbegin(); it != members.rend(); ++it) drawMember(*it);
  backend_->fetchResults(visible_);

  // Offsets of each member's answers in pass 1 and pass 2.
  std::size_t total = 0;
  for (const auto& m : members) total += m.triangles.size();
  std::vector<SetMember> kept;
  std::size_t first1 = 0;
  std::size_t end2 = 2 * total;  // pass 2 runs members in reverse, so member i ends where i-1 began
  for (auto& m : members) {
    const std::size_t count = m.triangles.size();
    const std::size_t first2 = end2 - count;
    SetMember out{m.object, {}};
    for (std::size_t k = 0; k < count; ++k)
      if (!(visible_[first1 + k] && visible_[first2 + k])) out.triangles.push_back(m.triangles[k]);
    first1 += count;
    end2 = first2;
    if (!out.triangles.empty()) kept.push_back(std::move(out));
  }
  members.swap(kept);
}

CullingResult Cullide::cull(const FrameInput& frame) {
  const VisibilityCounters before = backend_->counters();
  backend_->setPoses(frame.poses);
  bounds_.update(frame.poses);

  std::vector<ObjectId> pcs(scene_->objectCount());
  for (std::size_t i = 0; i < pcs.size(); ++i) pcs[i] = static_cast<ObjectId>(i);
  for (const auto& axis : kAxes) pruneObjects(pcs, axis);

  std::vector<SetMember> members;
  for (ObjectId o : pcs) {
    SetMember m{o, {}};
    m.triangles.resize(scene_->meshOf(o).triangleCount());
    for (std::uint32_t t = 0; t < m.triangles.size(); ++t) m.triangles[t] = t;
    members.push_back(std::move(m));
  }
  for (const auto& axis : kAxes) pruneTriangles(members, axis);

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
