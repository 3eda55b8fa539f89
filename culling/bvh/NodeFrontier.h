#pragma once
// The nodes of each object's OBB tree still in play during a coarse-to-fine traversal (thesis
// 3.4): every object starts at its root; a level's visibility tests prune nodes; expanding
// replaces each surviving internal node by its children while surviving leaves stay. What is
// left at the end goes to the exact phase as the triangles of the surviving nodes.
#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "core/Aabb.h"
#include "core/Pose.h"
#include "culling/PotentiallyCollidingSets.h"
#include "culling/bvh/SceneHierarchies.h"

namespace cdb {

class NodeFrontier {
 public:
  // `hierarchies` must outlive the frontier and stay built for the scene.
  void attach(const SceneGeometry& scene, const SceneHierarchies& hierarchies);

  // Every object back at its root.
  void reset();

  [[nodiscard]] const ObbTree& tree(ObjectId object) const {
    return hierarchies_->ofObject(object);
  }
  // Indices into tree(object).nodes() of the object's active nodes.
  [[nodiscard]] std::span<const std::uint32_t> nodes(ObjectId object) const {
    return active_[object];
  }
  // The box drawn for a node: fitted to its own triangles (MeshHierarchy::ownBoxes).
  [[nodiscard]] const OrientedBox& box(ObjectId object, std::uint32_t node) const {
    return hierarchies_->ownBox(object, node);
  }
  [[nodiscard]] bool allLeaves(ObjectId object) const;

  // Keeps the k-th active node of `object` where keep[k] is non-zero (keep.size() equals
  // nodes(object).size()). Returns how many are kept.
  std::size_t retain(ObjectId object, std::span<const std::uint8_t> keep);
  // Drops every node of the object: it has left the traversal.
  void clear(ObjectId object) { active_[object].clear(), worldBoxes_[object].clear(); }
  // Children of every active internal node replace it; active leaves stay.
  void expand(ObjectId object);

  // World AABB of the object's active nodes under `pose` (empty when none are). Each node's is
  // kept until the frontier of the object changes other than by retain(), or the pose does.
  [[nodiscard]] Aabb worldBounds(ObjectId object, const Pose& pose) const;
  // [Min, Max] of the object's active nodes along the unit `direction` under `pose`.
  [[nodiscard]] std::pair<double, double> interval(ObjectId object, const Pose& pose,
                                                   const Eigen::Vector3d& direction) const;
  // The same per active node, appended to `out` in the frontier's order; returns their union.
  std::pair<double, double> nodeIntervals(ObjectId object, const Pose& pose,
                                          const Eigen::Vector3d& direction,
                                          std::vector<std::pair<double, double>>& out) const;

  // Triangles of the object's active nodes.
  [[nodiscard]] std::size_t triangleCount(ObjectId object) const;
  // The object with the (local, ascending) triangles of its active nodes; no list when the nodes
  // still cover the whole mesh (SetMember's "every triangle").
  [[nodiscard]] SetMember member(ObjectId object) const;

 private:
  const SceneGeometry* scene_ = nullptr;
  const SceneHierarchies* hierarchies_ = nullptr;
  std::vector<std::vector<std::uint32_t>> active_;  // per object
  std::vector<std::uint32_t> scratch_;
  // Per object, the world boxes of its active nodes (in their order) under worldPose_, when
  // worldKept_ (worldBounds' per-node boxes, made once for a level's three axes).
  mutable std::vector<std::vector<Aabb>> worldBoxes_;
  mutable std::vector<Pose> worldPose_;
  mutable std::vector<std::uint8_t> worldKept_;
};

}  // namespace cdb
