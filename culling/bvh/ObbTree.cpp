#include "culling/bvh/ObbTree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

#include "core/Errors.h"
#include "culling/bvh/ObbFitting.h"

namespace cdb {
namespace {

void checkOptions(const Mesh& mesh, const ObbTreeOptions& options) {
  if (options.branching != 2 && options.branching != 4 && options.branching != 8)
    throw InputError("OBB tree: branching must be 2, 4 or 8, got " +
                     std::to_string(options.branching));
  if (options.leafTriangles < 1)
    throw InputError("OBB tree: leaf triangles must be at least 1, got " +
                     std::to_string(options.leafTriangles));
  if (!(options.offset >= 0) || !std::isfinite(options.offset))
    throw InputError("OBB tree: offset must be finite and >= 0, got " +
                     std::to_string(options.offset));
  if (mesh.triangles.size() >= std::numeric_limits<std::uint32_t>::max())
    throw InputError("OBB tree: mesh '" + mesh.name + "' has too many triangles (" +
                     std::to_string(mesh.triangles.size()) + ")");
}

struct Range {
  std::uint32_t first = 0;
  std::uint32_t count = 0;
};

// Reorders order[range] so that its lower half (by centroid along `axis`, then by triangle index)
// comes first, and returns the two halves.
std::array<Range, 2> splitAtMedian(std::vector<std::uint32_t>& order, Range range,
                                   const std::vector<Eigen::Vector3d>& centroids,
                                   const Eigen::Vector3d& axis,
                                   std::vector<std::pair<double, std::uint32_t>>& scratch) {
  scratch.clear();
  for (std::uint32_t i = range.first; i < range.first + range.count; ++i)
    scratch.emplace_back(axis.dot(centroids[order[i]]), order[i]);
  const std::uint32_t lower = range.count / 2;
  std::nth_element(scratch.begin(), scratch.begin() + lower, scratch.end());
  for (std::uint32_t i = 0; i < range.count; ++i) order[range.first + i] = scratch[i].second;
  return {Range{range.first, lower}, Range{range.first + lower, range.count - lower}};
}

// The node's box from its triangles alone, grown by the offset.
OrientedBox ownBox(const Mesh& mesh, std::span<const std::uint32_t> triangles,
                   const ObbTreeOptions& options) {
  if (triangles.empty()) return {};
  const std::vector<Eigen::Vector3d> vertices = verticesOf(mesh, triangles);
  const Eigen::Matrix3d principal = principalAxes(triangleCovariance(mesh, triangles));
  const OrientedBox box =
      options.optimized ? optimizedBox(vertices, principal) : boxAlongAxes(vertices, principal);
  return grown(box, options.offset);
}

// Fitted on their own, children's boxes poke out of their parent's even though their triangles
// cannot: an octant of a split node mostly reaches three faces of the parent, and would need the
// parent's orientation to stay inside. Rather than giving up the children's tight boxes (which
// decide what is left at the finest level), the parent grows to contain them: the smallest of its
// own axes and the (optimized) principal axes of all the corners, around its own box and its
// children's.
OrientedBox enclosingBox(const OrientedBox& own, std::span<const ObbTreeNode> children,
                         bool optimized) {
  std::vector<Eigen::Vector3d> corners;
  corners.reserve(8 * (children.size() + 1));
  for (int i = 0; i < 8; ++i) corners.push_back(own.corner(i));
  for (const ObbTreeNode& child : children)
    for (int i = 0; i < 8; ++i) corners.push_back(child.box.corner(i));
  OrientedBox best = boxAlongAxes(corners, own.axes);
  const Eigen::Matrix3d principal = principalAxes(pointCovariance(corners));
  const OrientedBox refitted =
      optimized ? optimizedBox(corners, principal) : boxAlongAxes(corners, principal);
  if (smallerBox(refitted, best)) best = refitted;
  return best;
}

}  // namespace

ObbTree ObbTree::build(const Mesh& mesh, const ObbTreeOptions& options) {
  checkOptions(mesh, options);
  const int splitAxes = options.branching == 8 ? 3 : options.branching == 4 ? 2 : 1;
  const auto triangleCount = std::uint32_t(mesh.triangles.size());

  ObbTree tree;
  tree.order_.resize(triangleCount);
  std::iota(tree.order_.begin(), tree.order_.end(), 0u);
  std::vector<Eigen::Vector3d> centroids;
  centroids.reserve(triangleCount);
  for (const auto& t : mesh.triangles) {
    centroids.push_back((mesh.vertices[t[0]].cast<double>() + mesh.vertices[t[1]].cast<double>() +
                         mesh.vertices[t[2]].cast<double>()) /
                        3.0);
  }

  // Top down: nodes are appended as their parent is split and processed in index order, which is
  // breadth-first.
  tree.nodes_.push_back({.box = {}, .triangleCount = triangleCount});
  std::vector<std::pair<double, std::uint32_t>> scratch;
  for (std::uint32_t n = 0; n < tree.nodes_.size(); ++n) {
    const ObbTreeNode node = tree.nodes_[n];
    const OrientedBox box = ownBox(mesh, tree.triangles(node), options);
    tree.nodes_[n].box = box;
    if (node.triangleCount <= std::uint32_t(options.leafTriangles)) continue;

    // Longest box axis first, so a binary or quaternary tree still halves the widest spread.
    std::array<int, 3> axisOrder{0, 1, 2};
    std::stable_sort(axisOrder.begin(), axisOrder.end(),
                     [&](int a, int b) { return box.halfExtents[a] > box.halfExtents[b]; });
    std::vector<Range> parts{{node.firstTriangle, node.triangleCount}};
    for (int s = 0; s < splitAxes; ++s) {
      std::vector<Range> halves;
      for (const Range& part : parts) {
        for (const Range& half :
             splitAtMedian(tree.order_, part, centroids, box.axes.col(axisOrder[s]), scratch))
          if (half.count > 0) halves.push_back(half);
      }
      parts = std::move(halves);
    }
    tree.nodes_[n].firstChild = std::uint32_t(tree.nodes_.size());
    tree.nodes_[n].childCount = std::uint32_t(parts.size());
    for (const Range& part : parts) {
      tree.nodes_.push_back({.box = {},
                             .firstTriangle = part.first,
                             .triangleCount = part.count,
                             .depth = node.depth + 1});
    }
  }

  // Bottom up: children come after their parent, so reverse order sees every child final first.
  for (std::uint32_t n = std::uint32_t(tree.nodes_.size()); n-- > 0;) {
    ObbTreeNode& node = tree.nodes_[n];
    if (!node.leaf()) {
      node.box =
          enclosingBox(node.box, std::span(tree.nodes_).subspan(node.firstChild, node.childCount),
                       options.optimized);
    }
  }

  for (std::uint32_t n = 1; n < tree.nodes_.size(); ++n)
    if (tree.nodes_[n].depth != tree.nodes_[n - 1].depth) tree.levelStart_.push_back(n);
  tree.levelStart_.push_back(std::uint32_t(tree.nodes_.size()));
  return tree;
}

}  // namespace cdb
