// The shared pieces of the hierarchy strategies: the process-wide OBB tree cache, the tree
// options a config gives, and the frontier of active nodes.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "culling/SortedIntervals.h"
#include "culling/bvh/NodeFrontier.h"
#include "culling/bvh/SceneHierarchies.h"
#include "scenes/ProceduralMeshes.h"

namespace cdb {
namespace {

// A torus no other test builds, so the cache counts start from it.
Mesh unusualTorus() { return makeTorus(0.53, 0.17, 7, 9); }

TEST(SceneHierarchies, TreeIsBuiltOncePerMeshContentAndOptions) {
  const Mesh mesh = unusualTorus();
  const ObbTreeOptions options{.leafTriangles = 5, .offset = 0.01};
  const std::uint64_t before = obbTreeBuilds();
  const auto first = cachedObbTree(mesh, options);
  EXPECT_EQ(obbTreeBuilds(), before + 1);

  Mesh copy = mesh;
  copy.name = "another name, same content";
  EXPECT_EQ(cachedObbTree(copy, options).get(), first.get());
  EXPECT_EQ(obbTreeBuilds(), before + 1);

  ObbTreeOptions other = options;
  other.leafTriangles = 6;
  EXPECT_NE(cachedObbTree(mesh, other).get(), first.get());
  EXPECT_EQ(obbTreeBuilds(), before + 2);

  Mesh moved = mesh;
  moved.vertices[0].x() += 0.01f;
  EXPECT_NE(cachedObbTree(moved, options).get(), first.get());
  EXPECT_EQ(obbTreeBuilds(), before + 3);
}

TEST(SceneHierarchies, ScenesOnTheSameMeshesShareTheirTrees) {
  SceneGeometry scene;
  scene.meshes.push_back(makeTorus(0.51, 0.19, 6, 10));
  for (int i = 0; i < 4; ++i) scene.objects.push_back({0, false, "torus"});
  HierarchySpec spec;
  spec.leafTriangles = 3;
  const std::uint64_t before = obbTreeBuilds();
  SceneHierarchies a;
  a.build(scene, spec);
  SceneHierarchies b;
  b.build(scene, spec);
  EXPECT_EQ(obbTreeBuilds(), before + 1);
  EXPECT_EQ(&a.ofObject(0), &a.ofObject(3));
  EXPECT_EQ(&a.ofObject(2), &b.ofMesh(0));
}

TEST(SceneHierarchies, TreeOptionsAreTheConfigsWithTheOffsetAFractionOfTheMeshDiagonal) {
  const Mesh mesh = makeTorus(0.5, 0.2, 20, 20);
  HierarchySpec spec;
  spec.branching = 4;
  spec.leafTriangles = 16;
  spec.offset = 0.01;
  const ObbTreeOptions options = hierarchyOptions(mesh, spec);
  EXPECT_EQ(options.branching, 4);
  EXPECT_EQ(options.leafTriangles, 16);
  EXPECT_DOUBLE_EQ(options.offset, 0.01 * mesh.bounds().diagonal().norm());
}

TEST(SceneHierarchies, OwnBoxesHoldTheirTrianglesAndAreNoLargerThanTheTreeBoxes) {
  const Mesh mesh = makeTorus(0.5, 0.2, 20, 20);
  const auto h = cachedHierarchy(mesh, ObbTreeOptions{.leafTriangles = 16, .offset = 1e-3});
  ASSERT_EQ(h->ownBoxes.size(), h->tree.nodes().size());
  for (std::uint32_t n = 0; n < h->ownBoxes.size(); ++n) {
    const OrientedBox& own = h->ownBoxes[n];
    EXPECT_LE(own.volume(), h->tree.nodes()[n].box.volume() * (1 + 1e-9)) << "node " << n;
    for (std::uint32_t t : h->tree.triangles(h->tree.nodes()[n]))
      for (std::uint32_t v : mesh.triangles[t]) {
        const Eigen::Vector3d local =
            own.axes.transpose() * (mesh.vertices[v].cast<double>() - own.center);
        EXPECT_TRUE((local.cwiseAbs() - own.halfExtents).maxCoeff() <= 1e-9) << "node " << n;
      }
  }
  // The root's own box is markedly tighter than the tree's (which holds its children's boxes).
  EXPECT_LT(h->ownBoxes[0].volume(), 0.8 * h->tree.nodes()[0].box.volume());
}

struct FrontierScene {
  SceneGeometry scene;
  SceneHierarchies hierarchies;
  std::vector<Pose> poses;
};

FrontierScene twoTori() {
  FrontierScene s;
  s.scene.meshes.push_back(makeTorus(0.5, 0.2, 8, 8));  // 128 triangles
  s.scene.objects.push_back({0, false, "torus"});
  s.scene.objects.push_back({0, false, "torus"});
  HierarchySpec spec;
  spec.leafTriangles = 4;
  s.hierarchies.build(s.scene, spec);
  Pose p;
  p.rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized());
  p.translation = {0.3, -1, 2};
  s.poses = {Pose{}, p};
  return s;
}

TEST(NodeFrontier, ExpandsLevelByLevelAndLeavesStay) {
  auto s = twoTori();
  NodeFrontier f;
  f.attach(s.scene, s.hierarchies);
  const ObbTree& tree = f.tree(0);
  ASSERT_GE(tree.levels(), 3u);
  EXPECT_EQ(std::vector<std::uint32_t>(f.nodes(0).begin(), f.nodes(0).end()),
            std::vector<std::uint32_t>{0});

  // Expanding d times reaches every node of depth d, plus the leaves above it.
  for (std::uint32_t depth = 1; depth < tree.levels(); ++depth) {
    f.expand(0);
    std::vector<std::uint32_t> expected;
    for (std::uint32_t n = 0; n < tree.nodes().size(); ++n) {
      const auto& node = tree.nodes()[n];
      if (node.depth == depth || (node.depth < depth && node.leaf())) expected.push_back(n);
    }
    std::vector<std::uint32_t> got(f.nodes(0).begin(), f.nodes(0).end());
    std::ranges::sort(got);
    EXPECT_EQ(got, expected) << "depth " << depth;
  }
  EXPECT_TRUE(f.allLeaves(0));
  EXPECT_FALSE(f.allLeaves(1));
  const auto leaves = std::vector<std::uint32_t>(f.nodes(0).begin(), f.nodes(0).end());
  f.expand(0);
  EXPECT_EQ(std::vector<std::uint32_t>(f.nodes(0).begin(), f.nodes(0).end()), leaves);

  f.reset();
  EXPECT_EQ(f.nodes(0).size(), 1u);
  EXPECT_EQ(f.nodes(0)[0], 0u);
}

TEST(NodeFrontier, MemberCarriesTheTrianglesOfTheActiveNodes) {
  auto s = twoTori();
  NodeFrontier f;
  f.attach(s.scene, s.hierarchies);
  f.expand(0);
  EXPECT_TRUE(f.member(0).allTriangles());  // nothing pruned yet
  EXPECT_EQ(f.triangleCount(0), 128u);

  const auto nodes = std::vector<std::uint32_t>(f.nodes(0).begin(), f.nodes(0).end());
  ASSERT_GE(nodes.size(), 3u);
  std::vector<std::uint8_t> keep(nodes.size(), 0);
  keep[0] = keep[2] = 1;
  EXPECT_EQ(f.retain(0, keep), 2u);
  std::vector<std::uint32_t> expected;
  for (std::uint32_t n : {nodes[0], nodes[2]}) {
    const auto tris = f.tree(0).triangles(f.tree(0).nodes()[n]);
    expected.insert(expected.end(), tris.begin(), tris.end());
  }
  std::ranges::sort(expected);
  const SetMember m = f.member(0);
  EXPECT_EQ(m.object, 0u);
  EXPECT_EQ(m.triangles, expected);
  EXPECT_EQ(f.triangleCount(0), expected.size());

  f.clear(0);
  EXPECT_TRUE(f.nodes(0).empty());
}

TEST(NodeFrontier, WorldBoundsAndIntervalsHoldTheActiveNodesTriangles) {
  auto s = twoTori();
  NodeFrontier f;
  f.attach(s.scene, s.hierarchies);
  const Mesh& mesh = s.scene.meshes[0];
  for (int level = 0; level < 3; ++level) {
    const Aabb world = f.worldBounds(1, s.poses[1]);
    for (std::uint32_t n : f.nodes(1))
      for (std::uint32_t t : f.tree(1).triangles(f.tree(1).nodes()[n]))
        for (std::uint32_t v : mesh.triangles[t])
          EXPECT_TRUE(world.contains(s.poses[1].apply(mesh.vertices[v].cast<double>())));
    for (int axis = 0; axis < 3; ++axis) {
      const auto [lo, hi] = f.interval(1, s.poses[1], Eigen::Vector3d::Unit(axis));
      const auto [alo, ahi] = projectAabb(world, Eigen::Vector3d::Unit(axis));
      EXPECT_NEAR(lo, alo, 1e-12);
      EXPECT_NEAR(hi, ahi, 1e-12);
    }
    f.expand(1);
  }
}

// worldBounds keeps each node's box from one call to the next: after a retain, under another
// pose, after an expand and a clear it answers as a frontier that never asked before.
TEST(NodeFrontier, WorldBoundsKeptAcrossCallsAnswerAsMadeAfresh) {
  auto s = twoTori();
  NodeFrontier kept, fresh;
  kept.attach(s.scene, s.hierarchies);
  fresh.attach(s.scene, s.hierarchies);
  kept.expand(1), fresh.expand(1);
  const Aabb all = kept.worldBounds(1, s.poses[1]);
  EXPECT_FALSE(all.isEmpty());
  std::vector<std::uint8_t> keep(kept.nodes(1).size(), 0);
  ASSERT_GE(keep.size(), 3u);
  keep[1] = 1;
  kept.retain(1, keep), fresh.retain(1, keep);
  const Aabb one = kept.worldBounds(1, s.poses[1]);
  EXPECT_TRUE(one.isApprox(fresh.worldBounds(1, s.poses[1]), 0.0));
  EXPECT_FALSE(one.isApprox(all, 1e-9)) << "one node's box is smaller than the object's";
  Pose moved = s.poses[1];
  moved.translation += Eigen::Vector3d(0.5, -0.25, 2.0);
  NodeFrontier other;
  other.attach(s.scene, s.hierarchies);
  other.expand(1), other.retain(1, keep);
  EXPECT_TRUE(kept.worldBounds(1, moved).isApprox(other.worldBounds(1, moved), 0.0));
  EXPECT_TRUE(kept.worldBounds(1, moved).isApprox(one.translated(moved.translation -
                                                                 s.poses[1].translation), 1e-12));
  kept.expand(1), fresh.expand(1);
  EXPECT_TRUE(kept.worldBounds(1, s.poses[1]).isApprox(fresh.worldBounds(1, s.poses[1]), 0.0));
  kept.clear(1);
  EXPECT_TRUE(kept.worldBounds(1, s.poses[1]).isEmpty());
}

}  // namespace
}  // namespace cdb
