#include "culling/bvh/NodeFrontier.h"

#include <algorithm>
#include <bit>

namespace cdb {

void NodeFrontier::attach(const SceneGeometry& scene, const SceneHierarchies& hierarchies) {
  scene_ = &scene;
  hierarchies_ = &hierarchies;
  active_.assign(scene.objectCount(), {});
  worldBoxes_.assign(scene.objectCount(), {});
  worldPose_.assign(scene.objectCount(), Pose{});
  worldKept_.assign(scene.objectCount(), 0);
  reset();
}

void NodeFrontier::reset() {
  for (auto& nodes : active_) nodes.assign(1, 0u);
  std::ranges::fill(worldKept_, 0);
}

bool NodeFrontier::allLeaves(ObjectId object) const {
  const auto& all = tree(object).nodes();
  return std::ranges::all_of(active_[object], [&](std::uint32_t n) { return all[n].leaf(); });
}

std::size_t NodeFrontier::retain(ObjectId object, std::span<const std::uint8_t> keep) {
  auto& nodes = active_[object];
  auto& boxes = worldBoxes_[object];
  const bool withBoxes = worldKept_[object] != 0;
  std::size_t kept = 0;
  for (std::size_t k = 0; k < nodes.size(); ++k)
    if (keep[k]) {
      if (withBoxes) boxes[kept] = boxes[k];
      nodes[kept++] = nodes[k];
    }
  nodes.resize(kept);
  if (withBoxes) boxes.resize(kept);
  return kept;
}

void NodeFrontier::expand(ObjectId object) {
  const auto& all = tree(object).nodes();
  scratch_.clear();
  for (std::uint32_t n : active_[object]) {
    const ObbTreeNode& node = all[n];
    if (node.leaf()) {
      scratch_.push_back(n);
    } else {
      for (std::uint32_t c = 0; c < node.childCount; ++c) scratch_.push_back(node.firstChild + c);
    }
  }
  active_[object].swap(scratch_);
  worldKept_[object] = 0;
}

Aabb NodeFrontier::worldBounds(ObjectId object, const Pose& pose) const {
  std::vector<Aabb>& boxes = worldBoxes_[object];
  const Pose& kept = worldPose_[object];
  if (worldKept_[object] == 0 || kept.rotation.coeffs() != pose.rotation.coeffs() ||
      kept.translation != pose.translation) {
    const Eigen::Matrix3d r = pose.rotation.toRotationMatrix();
    boxes.clear();
    for (std::uint32_t n : active_[object]) {
      const OrientedBox& b = box(object, n);
      const Eigen::Vector3d c = pose.apply(b.center);
      const Eigen::Vector3d h = (r * b.axes).cwiseAbs() * b.halfExtents;
      boxes.emplace_back(c - h, c + h);
    }
    worldPose_[object] = pose;
    worldKept_[object] = 1;
  }
  Aabb result;
  for (const Aabb& b : boxes) result.extend(b);
  return result;
}

std::pair<double, double> NodeFrontier::nodeIntervals(
    ObjectId object, const Pose& pose, const Eigen::Vector3d& direction,
    std::vector<std::pair<double, double>>& out) const {
  // The direction in the object's frame: one rotation per object instead of one per node.
  const Eigen::Vector3d local = pose.rotation.conjugate() * direction;
  const double offset = direction.dot(pose.translation);
  double lo = 0;
  double hi = 0;
  bool first = true;
  for (std::uint32_t n : active_[object]) {
    const OrientedBox& b = box(object, n);
    const double c = local.dot(b.center) + offset;
    const double h = (b.axes.transpose() * local).cwiseAbs().dot(b.halfExtents);
    out.emplace_back(c - h, c + h);
    lo = first ? c - h : std::min(lo, c - h);
    hi = first ? c + h : std::max(hi, c + h);
    first = false;
  }
  return {lo, hi};
}

std::pair<double, double> NodeFrontier::interval(ObjectId object, const Pose& pose,
                                                 const Eigen::Vector3d& direction) const {
  std::vector<std::pair<double, double>> perNode;
  return nodeIntervals(object, pose, direction, perNode);
}

std::size_t NodeFrontier::triangleCount(ObjectId object) const {
  const auto& all = tree(object).nodes();
  std::size_t count = 0;
  for (std::uint32_t n : active_[object]) count += all[n].triangleCount;
  return count;
}

SetMember NodeFrontier::member(ObjectId object) const {
  SetMember m{object, {}};
  // Active nodes never share a triangle (no node is an ancestor of another), so the counts add.
  const std::size_t all = scene_->meshOf(object).triangleCount();
  const std::size_t count = triangleCount(object);
  if (count == all) return m;
  const ObbTree& t = tree(object);
  m.triangles.reserve(count);
  // In ascending order without a sort: marked in a bitmap over the mesh's triangles, read back.
  std::vector<std::uint64_t> marked((all + 63) / 64);
  for (std::uint32_t n : active_[object])
    for (std::uint32_t tri : t.triangles(t.nodes()[n]))
      marked[tri / 64] |= std::uint64_t{1} << (tri % 64);
  for (std::size_t w = 0; w < marked.size(); ++w)
    for (std::uint64_t bits = marked[w]; bits != 0; bits &= bits - 1)
      m.triangles.push_back(static_cast<std::uint32_t>(w * 64 + std::countr_zero(bits)));
  return m;
}

}  // namespace cdb
