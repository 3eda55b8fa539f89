#include "culling/exact/ReferenceTree.h"

#include <algorithm>
#include <numeric>

namespace cdb {

namespace {

struct Builder {
  const std::vector<Eigen::Vector3d>& centroids;
  ReferenceTree& tree;

  void split(std::uint32_t first, std::uint32_t count) {
    const auto self = std::uint32_t(tree.nodes.size());
    tree.nodes.push_back({first, count, 0});
    if (count <= ReferenceTree::kLeafTriangles) return;

    Aabb spread;
    for (std::uint32_t k = first; k < first + count; ++k) spread.extend(centroids[tree.order[k]]);
    int axis = 0;
    spread.sizes().maxCoeff(&axis);
    // The median always halves the range, so the depth stays logarithmic even when centroids
    // coincide.
    const std::uint32_t half = count / 2;
    const auto begin = tree.order.begin() + first;
    std::nth_element(begin, begin + half, begin + count, [&](std::uint32_t a, std::uint32_t b) {
      return centroids[a][axis] < centroids[b][axis];
    });

    tree.nodes[self].count = 0;
    split(first, half);
    tree.nodes[self].right = std::uint32_t(tree.nodes.size());
    split(first + half, count - half);
  }
};

}  // namespace

ReferenceTree ReferenceTree::build(const Mesh& mesh) {
  ReferenceTree tree;
  const auto n = std::uint32_t(mesh.triangleCount());
  if (n == 0) return tree;
  std::vector<Eigen::Vector3d> centroids(n);
  for (std::uint32_t t = 0; t < n; ++t) {
    const Triangle& tri = mesh.triangles[t];
    centroids[t] = (mesh.vertices[tri[0]].cast<double>() + mesh.vertices[tri[1]].cast<double>() +
                    mesh.vertices[tri[2]].cast<double>()) /
                   3.0;
  }
  tree.order.resize(n);
  std::iota(tree.order.begin(), tree.order.end(), 0u);
  tree.nodes.reserve(2 * (n / kLeafTriangles + 1));
  Builder{centroids, tree}.split(0, n);
  return tree;
}

void WorldTree::refit(const ReferenceTree& tree, const Mesh& mesh, const Pose& pose) {
  // The same world transform, written the same way, as the exact phase's: both then hand the
  // triangle test bit-identical coordinates.
  const Eigen::Matrix3d r = pose.rotation.toRotationMatrix();
  vertices.resize(mesh.vertices.size());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    vertices[v] = r * mesh.vertices[v].cast<double>() + pose.translation;

  boxes.resize(tree.nodes.size());
  // Children follow their parent in the array, so a backward pass sees them first.
  for (std::size_t i = tree.nodes.size(); i-- > 0;) {
    const ReferenceTree::Node& node = tree.nodes[i];
    Aabb box;
    if (node.isLeaf()) {
      for (std::uint32_t k = node.first; k < node.first + node.count; ++k)
        for (std::uint32_t v : mesh.triangles[tree.order[k]]) box.extend(vertices[v]);
    } else {
      box = boxes[i + 1].merged(boxes[node.right]);
    }
    boxes[i] = box;
  }
}

}  // namespace cdb
