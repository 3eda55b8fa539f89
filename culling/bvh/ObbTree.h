#pragma once
// The thesis' bounding-volume hierarchy (3.4.1): a top-down 8-ary tree of oriented boxes per mesh,
// built once in the mesh's local frame. Eight children per node instead of two keep the tree
// shallow, since culling clears the frame buffer once per level.
#include <cstdint>
#include <span>
#include <vector>

#include "core/OrientedBox.h"
#include "scenes/Mesh.h"

namespace cdb {

struct ObbTreeOptions {
  int branching = 8;      // children per split: 2, 4 or 8 (medians along 1, 2 or 3 box axes)
  int leafTriangles = 8;  // a node with at most this many triangles is a leaf (>= 1)
  double offset = 0;      // added to every half extent, an absolute distance in mesh units (>= 0)
  bool optimized = true;  // optimizing principal components instead of the plain covariance box
};

struct ObbTreeNode {
  OrientedBox box;
  std::uint32_t firstChild = 0;
  std::uint32_t childCount = 0;
  std::uint32_t firstTriangle = 0;  // into ObbTree::triangleOrder()
  std::uint32_t triangleCount = 0;
  std::uint32_t depth = 0;

  [[nodiscard]] bool leaf() const { return childCount == 0; }
};

// Every node's box contains its triangles (with the offset to spare) and lies inside its parent's
// box; the children of a node split its triangles into disjoint non-empty parts.
class ObbTree {
 public:
  // Splits each node with more than leafTriangles triangles at the median triangle centroid along
  // its box's longest axis, each half at its own median along the next axis, and so on, dropping
  // empty parts; ties in the centroid go by triangle index, so coincident centroids still split.
  // A leaf's box is the fit of its triangles; an internal node's box is grown, bottom up, to
  // contain the fit of its own triangles and its children's boxes. Throws InputError for invalid
  // options.
  [[nodiscard]] static ObbTree build(const Mesh& mesh, const ObbTreeOptions& options);

  // Breadth-first: the root is node 0, each level is a contiguous range, and a node's children
  // are [firstChild, firstChild + childCount).
  [[nodiscard]] const std::vector<ObbTreeNode>& nodes() const { return nodes_; }

  // The node's triangles, as indices into the mesh's triangles: a contiguous range of
  // triangleOrder(), so every node (not only a leaf) is one slice of the same permutation.
  [[nodiscard]] std::span<const std::uint32_t> triangles(const ObbTreeNode& node) const {
    return std::span(order_).subspan(node.firstTriangle, node.triangleCount);
  }

  [[nodiscard]] std::uint32_t levels() const { return std::uint32_t(levelStart_.size() - 1); }

  // The nodes at depth d (the root's level is 0).
  [[nodiscard]] std::span<const ObbTreeNode> level(std::uint32_t d) const {
    return std::span(nodes_).subspan(levelStart_[d], levelStart_[d + 1] - levelStart_[d]);
  }

  // A permutation of the mesh's triangle indices; the mesh itself is left as it is.
  [[nodiscard]] const std::vector<std::uint32_t>& triangleOrder() const { return order_; }

 private:
  std::vector<ObbTreeNode> nodes_;
  std::vector<std::uint32_t> order_;
  std::vector<std::uint32_t> levelStart_{0};  // levels() + 1 entries, the last is nodes_.size()
};

}  // namespace cdb
