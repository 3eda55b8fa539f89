#pragma once
// The ground truth's bounding-volume hierarchy: a binary tree over a mesh's triangles, built once
// per mesh by median splits in the local frame, whose boxes are refitted around world-space
// vertices each frame (van den Bergen, "Efficient Collision Detection of Complex Deformable Models
// using AABB Trees", JGT 1997). Refitting keeps every box the exact hull of the coordinates the
// triangle test sees, so no tolerance is needed.
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "core/Aabb.h"
#include "core/Pose.h"
#include "scenes/Mesh.h"

namespace cdb {

struct ReferenceTree {
  static constexpr std::uint32_t kLeafTriangles = 4;

  // Nodes in depth-first order: an inner node's left child follows it, its right child is at
  // `right`; a leaf holds `order[first, first + count)`.
  struct Node {
    std::uint32_t first = 0;
    std::uint32_t count = 0;  // 0 for inner nodes
    std::uint32_t right = 0;
    [[nodiscard]] bool isLeaf() const { return count != 0; }
  };

  std::vector<Node> nodes;
  std::vector<std::uint32_t> order;  // triangle indices, grouped by leaf

  [[nodiscard]] static ReferenceTree build(const Mesh& mesh);
};

// One object's tree in world space for one frame.
struct WorldTree {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Aabb> boxes;  // one per node of the mesh's tree

  void refit(const ReferenceTree& tree, const Mesh& mesh, const Pose& pose);
};

}  // namespace cdb
