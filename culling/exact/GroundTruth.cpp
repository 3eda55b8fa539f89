#include "culling/exact/GroundTruth.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "culling/exact/ReferenceTree.h"
#include "culling/exact/TriangleTriangle.h"

namespace cdb {

struct GroundTruth::Impl {
  const SceneGeometry& scene;
  std::vector<ReferenceTree> trees;  // per mesh
  std::vector<Aabb> meshBounds;      // per mesh, local frame
};

GroundTruth::GroundTruth(const SceneGeometry& scene)
    : impl_(std::make_unique<Impl>(Impl{scene, {}, {}})) {
  impl_->trees.reserve(scene.meshes.size());
  for (const Mesh& mesh : scene.meshes) {
    impl_->trees.push_back(ReferenceTree::build(mesh));
    impl_->meshBounds.push_back(mesh.bounds());
  }
}

GroundTruth::~GroundTruth() = default;
GroundTruth::GroundTruth(GroundTruth&&) noexcept = default;

namespace {

// A world box from transformAabb, widened past the rounding of vertices transformed one by one.
// It only decides which object pairs to descend into; the trees' refitted boxes are exact.
Aabb widened(Aabb box) {
  if (box.isEmpty()) return box;
  const double scale = box.min().cwiseAbs().cwiseMax(box.max().cwiseAbs()).maxCoeff();
  const Eigen::Vector3d slack = Eigen::Vector3d::Constant(1e-12 * scale + 1e-300);
  box.min() -= slack;
  box.max() += slack;
  return box;
}

struct PairCounts {
  std::uint64_t tests = 0;
  std::uint64_t hits = 0;
};

// Simultaneous descent of two refitted trees; the node with the larger box is split first.
PairCounts traverse(const ReferenceTree& ta, const WorldTree& wa, const Mesh& ma,
                    const ReferenceTree& tb, const WorldTree& wb, const Mesh& mb,
                    std::vector<std::pair<std::uint32_t, std::uint32_t>>& stack) {
  PairCounts counts;
  stack.clear();
  stack.emplace_back(0u, 0u);
  while (!stack.empty()) {
    const auto [a, b] = stack.back();
    stack.pop_back();
    if (!wa.boxes[a].intersects(wb.boxes[b])) continue;
    const ReferenceTree::Node& na = ta.nodes[a];
    const ReferenceTree::Node& nb = tb.nodes[b];
    if (na.isLeaf() && nb.isLeaf()) {
      for (std::uint32_t i = na.first; i < na.first + na.count; ++i) {
        const Triangle& x = ma.triangles[ta.order[i]];
        for (std::uint32_t j = nb.first; j < nb.first + nb.count; ++j) {
          const Triangle& y = mb.triangles[tb.order[j]];
          ++counts.tests;
          counts.hits +=
              trianglesIntersect(wa.vertices[x[0]], wa.vertices[x[1]], wa.vertices[x[2]],
                                 wb.vertices[y[0]], wb.vertices[y[1]], wb.vertices[y[2]]);
        }
      }
    } else if (nb.isLeaf() ||
               (!na.isLeaf() && wa.boxes[a].sizes().sum() >= wb.boxes[b].sizes().sum())) {
      stack.emplace_back(a + 1, b);
      stack.emplace_back(na.right, b);
    } else {
      stack.emplace_back(a, b + 1);
      stack.emplace_back(a, nb.right);
    }
  }
  return counts;
}

}  // namespace

CollisionReport GroundTruth::compute(std::span<const Pose> poses) const {
  const SceneGeometry& scene = impl_->scene;
  const std::size_t n = scene.objectCount();
  if (poses.size() < n)
    throw std::invalid_argument("ground truth: " + std::to_string(poses.size()) + " poses for " +
                                std::to_string(n) + " objects");

  std::vector<Aabb> worldBoxes(n);
  for (std::size_t o = 0; o < n; ++o)
    worldBoxes[o] = widened(transformAabb(impl_->meshBounds[scene.objects[o].mesh], poses[o]));

  std::vector<WorldTree> world(n);
  std::vector<bool> refitted(n, false);
  const auto worldTree = [&](std::size_t o) -> const WorldTree& {
    if (!refitted[o]) {
      world[o].refit(impl_->trees[scene.objects[o].mesh], scene.meshOf(ObjectId(o)), poses[o]);
      refitted[o] = true;
    }
    return world[o];
  };

  CollisionReport report;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> stack;
  for (std::size_t a = 0; a < n; ++a) {
    const ReferenceTree& ta = impl_->trees[scene.objects[a].mesh];
    if (ta.nodes.empty()) continue;
    for (std::size_t b = a + 1; b < n; ++b) {
      const ReferenceTree& tb = impl_->trees[scene.objects[b].mesh];
      if (tb.nodes.empty() || !worldBoxes[a].intersects(worldBoxes[b])) continue;
      const WorldTree& wa = worldTree(a);
      const WorldTree& wb = worldTree(b);
      ++report.pairsTested;
      const PairCounts counts =
          traverse(ta, wa, scene.meshOf(ObjectId(a)), tb, wb, scene.meshOf(ObjectId(b)), stack);
      report.triangleTests += counts.tests;
      report.collidingTrianglePairs += counts.hits;
      if (counts.hits > 0) report.collidingPairs.push_back({ObjectId(a), ObjectId(b)});
    }
  }
  return report;  // pairs come out sorted: a ascending, then b ascending
}

}  // namespace cdb
