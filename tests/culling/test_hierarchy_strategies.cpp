// cullide_bvh and ours against the scripted oracle: the coarse-to-fine control flow (level by
// level, an object's nodes all queried before any is written, pruned nodes not expanded, the
// surviving leaves' triangles in the output), ours' axis per level, passes per set, first object
// not queried and last not written, a set split at level 1; and on random scenes decided from
// the geometry, no pair of touching triangles lost.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>

#include "BoxGeometricOracle.h"
#include "BoxScenes.h"
#include "culling/strategies/CullideWithHierarchy.h"
#include "culling/strategies/HierarchicalCollisionIndependentSets.h"
#include "culling/visibility/ScriptedVisibilityOracle.h"
#include "scenes/ProceduralMeshes.h"

namespace cdb {
namespace {

using Kind = VisibilityCall::Kind;

HierarchySpec withLeaves(int leafTriangles) {
  HierarchySpec h;
  h.leafTriangles = leafTriangles;
  return h;
}

// Three tori of 32 triangles in a row along x, overlapping their neighbours.
struct ToriScene {
  SceneGeometry scene;
  std::vector<Pose> poses;
};
ToriScene threeToriWithPoses() {
  ToriScene s;
  s.scene.meshes.push_back(makeTorus(0.5, 0.2, 4, 4));
  for (int i = 0; i < 3; ++i) {
    s.scene.objects.push_back({0, false, "torus"});
    Pose p;
    p.translation = {0.9 * i, 0.1 * i, 0.05 * i};
    s.poses.push_back(p);
  }
  return s;
}

// The node whose drawn box (its own triangles' box) is `box`; boxes of one mesh are distinct.
std::uint32_t nodeOf(const MeshHierarchy& h, const OrientedBox& box) {
  for (std::uint32_t n = 0; n < h.ownBoxes.size(); ++n)
    if (h.ownBoxes[n].center == box.center && h.ownBoxes[n].halfExtents == box.halfExtents)
      return n;
  ADD_FAILURE() << "a drawn box is no node of the tree";
  return 0;
}

std::shared_ptr<const MeshHierarchy> hierarchyOf(const Mesh& mesh, const HierarchySpec& h) {
  return cachedHierarchy(mesh, hierarchyOptions(mesh, h));
}

bool inSubtree(const ObbTree& tree, std::uint32_t node, std::uint32_t root) {
  // Breadth-first: walk down from root over the node ranges.
  std::vector<std::uint32_t> stack{root};
  while (!stack.empty()) {
    const std::uint32_t n = stack.back();
    stack.pop_back();
    if (n == node) return true;
    const auto& nd = tree.nodes()[n];
    for (std::uint32_t c = 0; c < nd.childCount; ++c) stack.push_back(nd.firstChild + c);
  }
  return false;
}

// The frontier a traversal reaches at each level when nothing is pruned.
std::vector<std::vector<std::uint32_t>> unprunedLevels(const ObbTree& tree) {
  std::vector<std::vector<std::uint32_t>> levels{{0}};
  for (;;) {
    std::vector<std::uint32_t> next;
    bool internal = false;
    for (std::uint32_t n : levels.back()) {
      const auto& nd = tree.nodes()[n];
      internal |= !nd.leaf();
      if (nd.leaf()) next.push_back(n);
      for (std::uint32_t c = 0; c < nd.childCount; ++c) next.push_back(nd.firstChild + c);
    }
    if (!internal) return levels;
    levels.push_back(next);
  }
}

// The calls of each pass, grouped per pass.
std::vector<std::vector<const VisibilityCall*>> callsPerPass(const ScriptedVisibilityOracle& oracle) {
  std::vector<std::vector<const VisibilityCall*>> passes;
  for (const auto& c : oracle.log()) {
    if (c.kind == Kind::BeginPass) passes.emplace_back();
    if (!passes.empty()) passes.back().push_back(&c);
  }
  return passes;
}

// In every pass, each object's calls are contiguous and its queries all come before its writes.
void expectObjectsDrawnAsGroups(const ScriptedVisibilityOracle& oracle) {
  for (const auto& pass : callsPerPass(oracle)) {
    std::set<ObjectId> finished;
    ObjectId current = 0;
    bool any = false;
    bool writing = false;
    for (const VisibilityCall* c : pass) {
      if (c->kind == Kind::BeginPass) continue;
      if (!any || c->object != current) {
        EXPECT_FALSE(finished.count(c->object)) << "object " << c->object << " drawn twice";
        if (any) finished.insert(current);
        current = c->object;
        any = true;
        writing = false;
      }
      if (c->kind == Kind::WriteBox) writing = true;
      EXPECT_FALSE(c->kind == Kind::QueryBox && writing) << "object " << c->object;
    }
  }
}

// ---- cullide_bvh ---------------------------------------------------------------------------

TEST(CullideBvhOracle, NothingVisibleWalksEveryLevelAlongXYZAndKeepsEverything) {
  auto s = threeToriWithPoses();
  ScriptedVisibilityOracle oracle([](const VisibilityCall&, auto) { return false; });
  CullideWithHierarchy strategy(DetectorOptions{}, {withLeaves(2)});
  strategy.attach(s.scene, oracle);
  const auto result = strategy.cull({s.poses, 0});

  const auto hierarchy = hierarchyOf(s.scene.meshes[0], withLeaves(2));
  const ObbTree& tree = hierarchy->tree;
  const auto levels = unprunedLevels(tree);
  ASSERT_GE(levels.size(), 3u);
  ASSERT_EQ(result.counters.levels.size(), levels.size());
  const auto passes = callsPerPass(oracle);
  ASSERT_EQ(passes.size(), 6 * levels.size());
  for (std::size_t level = 0; level < levels.size(); ++level) {
    EXPECT_EQ(result.counters.levels[level].level, level);
    EXPECT_EQ(result.counters.levels[level].nodesTested, 3 * levels[level].size());
    EXPECT_EQ(result.counters.levels[level].nodesKept, 3 * levels[level].size());
    EXPECT_EQ(result.counters.levels[level].sets, 1u);
    EXPECT_EQ(result.counters.levels[level].queries, 6 * 3 * levels[level].size());
    for (int p = 0; p < 6; ++p) {
      const auto& pass = passes[6 * level + p];
      EXPECT_EQ(pass[0]->view.direction, Eigen::Vector3d::Unit(p / 2)) << "level " << level;
      EXPECT_EQ(pass[0]->depth, DepthUse::Fresh);
      // Pass 1 in order O1..On, pass 2 in reverse; each object its level's nodes.
      std::vector<ObjectId> order;
      for (const VisibilityCall* c : pass) {
        if (c->kind != Kind::QueryBox) continue;
        if (order.empty() || order.back() != c->object) order.push_back(c->object);
      }
      EXPECT_EQ(order,
                (p % 2 == 0 ? std::vector<ObjectId>{0, 1, 2} : std::vector<ObjectId>{2, 1, 0}));
      std::multiset<std::uint32_t> queried;
      for (const VisibilityCall* c : pass)
        if (c->kind == Kind::QueryBox && c->object == 1) queried.insert(nodeOf(*hierarchy, c->box));
      EXPECT_EQ(queried, std::multiset<std::uint32_t>(levels[level].begin(), levels[level].end()));
    }
  }
  expectObjectsDrawnAsGroups(oracle);

  ASSERT_EQ(result.sets.size(), 1u);
  ASSERT_EQ(result.sets[0].members.size(), 3u);
  for (const auto& m : result.sets[0].members) EXPECT_TRUE(m.allTriangles());
  EXPECT_EQ(result.counters.sets, 1u);
  EXPECT_EQ(result.counters.pcsSize, 3u);
  EXPECT_EQ(result.counters.pcsTriangles, 3u * 32);
  EXPECT_EQ(result.counters.visibility.fetches, 3 * levels.size());
}

TEST(CullideBvhOracle, PrunedNodesAreNotExpandedAndTheLeavesTrianglesComeOut) {
  auto s = threeToriWithPoses();
  const HierarchySpec leaves = withLeaves(2);
  const auto hierarchy = hierarchyOf(s.scene.meshes[0], leaves);
  const ObbTree& tree = hierarchy->tree;
  const std::uint32_t kept = tree.nodes()[0].firstChild + 1;  // one child of the root
  ASSERT_FALSE(tree.nodes()[kept].leaf());
  // Object 0: every node outside `kept`'s subtree is fully visible below the root.
  ScriptedVisibilityOracle oracle([&](const VisibilityCall& q, auto) {
    if (q.object != 0) return false;
    const std::uint32_t n = nodeOf(*hierarchy, q.box);
    return n != 0 && !inSubtree(tree, n, kept);
  });
  CullideWithHierarchy strategy(DetectorOptions{}, {leaves});
  strategy.attach(s.scene, oracle);
  const auto result = strategy.cull({s.poses, 0});

  for (const auto& c : oracle.log()) {
    if (c.kind != Kind::QueryBox || c.object != 0) continue;
    const std::uint32_t n = nodeOf(*hierarchy, c.box);
    EXPECT_TRUE(tree.nodes()[n].depth < 2 || inSubtree(tree, n, kept)) << "node " << n;
  }
  ASSERT_EQ(result.sets.size(), 1u);
  ASSERT_EQ(result.sets[0].members.size(), 3u);
  const SetMember& m0 = result.sets[0].members[0];
  EXPECT_EQ(m0.object, 0u);
  const auto tris = tree.triangles(tree.nodes()[kept]);
  std::vector<std::uint32_t> expected(tris.begin(), tris.end());
  std::ranges::sort(expected);
  EXPECT_EQ(m0.triangles, expected);
  EXPECT_EQ(result.counters.pcsTriangles, 2u * 32 + expected.size());
  // Level 1 keeps one of object 0's children; level 0 kept every root.
  EXPECT_EQ(result.counters.levels[0].nodesKept, 3u);
  EXPECT_EQ(result.counters.levels[1].nodesKept, 2 * tree.nodes()[0].childCount + 1);
}

TEST(CullideBvhOracle, EverythingFullyVisibleEndsAfterTheFirstAxis) {
  auto s = threeToriWithPoses();
  ScriptedVisibilityOracle oracle([](const VisibilityCall&, auto) { return true; });
  CullideWithHierarchy strategy(DetectorOptions{}, {withLeaves(2)});
  strategy.attach(s.scene, oracle);
  const auto result = strategy.cull({s.poses, 0});
  EXPECT_TRUE(result.sets.empty());
  EXPECT_EQ(result.counters.sets, 0u);
  EXPECT_EQ(result.counters.visibility.passes, 2u);
  EXPECT_EQ(result.counters.visibility.queries, 6u);
  ASSERT_EQ(result.counters.levels.size(), 1u);
  EXPECT_EQ(result.counters.levels[0].nodesKept, 0u);
}

TEST(CullideBvhOracle, AnObjectLeftAloneCollidesWithNothing) {
  auto s = threeToriWithPoses();
  // Object 1 is hidden in every pass, the others fully visible: it is left alone.
  ScriptedVisibilityOracle oracle([](const VisibilityCall& q, auto) { return q.object != 1; });
  CullideWithHierarchy strategy(DetectorOptions{}, {withLeaves(2)});
  strategy.attach(s.scene, oracle);
  const auto result = strategy.cull({s.poses, 0});
  EXPECT_TRUE(result.sets.empty());
  EXPECT_EQ(result.counters.pcsSize, 0u);
}

// ---- ours ----------------------------------------------------------------------------------

TEST(OursOracle, EachLevelLooksAlongTheNextAxisWithOnePassPairPerSet) {
  auto s = threeToriWithPoses();
  ScriptedVisibilityOracle oracle([](const VisibilityCall&, auto) { return false; });
  HierarchicalCollisionIndependentSets strategy(DetectorOptions{}, {1, withLeaves(2)});
  strategy.attach(s.scene, oracle);
  const auto result = strategy.cull({s.poses, 0});

  const auto& axes = strategy.lastFrame().axes;
  ASSERT_GE(axes.size(), 3u);
  for (std::size_t level = 0; level < axes.size(); ++level)
    EXPECT_EQ(axes[level], static_cast<int>((1 + level) % 3));
  // Nothing fully visible: one set all the way down, two passes per level sharing one clear.
  const auto passes = callsPerPass(oracle);
  ASSERT_EQ(passes.size(), 2 * axes.size());
  for (std::size_t p = 0; p < passes.size(); ++p) {
    const Eigen::Vector3d d = Eigen::Vector3d::Unit(axes[p / 2]);
    EXPECT_EQ(passes[p][0]->view.direction, p % 2 == 0 ? d : Eigen::Vector3d(-d));
    EXPECT_EQ(passes[p][0]->depth, p % 2 == 0 ? DepthUse::SharedFirst : DepthUse::SharedSecond);
  }
  EXPECT_EQ(result.counters.visibility.depthClears, axes.size());
  EXPECT_EQ(result.counters.visibility.fetches, axes.size());
  ASSERT_EQ(result.sets.size(), 1u);
  EXPECT_EQ(result.sets[0].members.size(), 3u);
  EXPECT_EQ(result.counters.levels.size(), axes.size());
  for (const auto& level : result.counters.levels) EXPECT_EQ(level.sets, 1u);
}

TEST(OursOracle, FirstObjectOfAPassIsNotQueriedAndTheLastNotWritten) {
  auto s = threeToriWithPoses();
  ScriptedVisibilityOracle oracle([](const VisibilityCall&, auto) { return false; });
  HierarchicalCollisionIndependentSets strategy(DetectorOptions{}, {0, withLeaves(2)});
  strategy.attach(s.scene, oracle);
  (void)strategy.cull({s.poses, 0});

  expectObjectsDrawnAsGroups(oracle);
  for (const auto& pass : callsPerPass(oracle)) {
    // Objects in drawing order, and whether each was queried / written.
    std::vector<ObjectId> order;
    std::map<ObjectId, std::pair<int, int>> calls;
    for (const VisibilityCall* c : pass) {
      if (c->kind == Kind::BeginPass) continue;
      if (order.empty() || order.back() != c->object) order.push_back(c->object);
      (c->kind == Kind::QueryBox ? calls[c->object].first : calls[c->object].second) += 1;
    }
    ASSERT_EQ(order.size(), 3u);
    EXPECT_EQ(calls[order.front()].first, 0) << "first object queried";
    EXPECT_GT(calls[order.front()].second, 0);
    EXPECT_EQ(calls[order.back()].second, 0) << "last object written";
    EXPECT_GT(calls[order.back()].first, 0);
    EXPECT_GT(calls[order[1]].first, 0);
    EXPECT_GT(calls[order[1]].second, 0);
  }
  // Pass 1 far to near along +x: decreasing x.
  const auto passes = callsPerPass(oracle);
  EXPECT_EQ(passes[0][1]->object, 2u);
  EXPECT_EQ(passes[1][1]->object, 0u);
}

// Four boxes overlapping along x: A and B touch at y in [0, 1.5], C and D at y in [7, 8.5] (far
// enough apart for the loose boxes of single-triangle nodes). Along x they form one set at
// level 0; along y they split at level 1.
testing::BoxScene twoPairs() {
  using testing::box;
  return testing::boxScene({box(0, 2, 0, 1, 0, 1), box(1, 3, 0.5, 1.5, 0.2, 1.2),
                            box(0.5, 2.5, 7, 8, 0, 1), box(1.5, 3.5, 7.5, 8.5, 0.3, 1.3)});
}

std::vector<std::vector<ObjectId>> objectSets(const CullingResult& r) {
  std::vector<std::vector<ObjectId>> out;
  for (const auto& s : r.sets) {
    std::vector<ObjectId> ids;
    for (const auto& m : s.members) ids.push_back(m.object);
    std::ranges::sort(ids);
    out.push_back(ids);
  }
  std::ranges::sort(out);
  return out;
}

TEST(OursOracle, ASetSplitsAtLevelOneAndEachSubsetHasItsOwnPasses) {
  auto s = twoPairs();
  testing::BoxGeometricOracle g;
  // Leaves of one triangle: a box mesh's tree then has three levels.
  HierarchicalCollisionIndependentSets strategy(DetectorOptions{}, {0, withLeaves(1)});
  strategy.attach(s.scene, g.backend());
  const auto result = strategy.cull({s.poses, 0});

  ASSERT_GE(result.counters.levels.size(), 3u);
  EXPECT_EQ(result.counters.levels[0].sets, 1u);
  EXPECT_EQ(result.counters.levels[1].sets, 2u);
  EXPECT_EQ(objectSets(result), (std::vector<std::vector<ObjectId>>{{0, 1}, {2, 3}}));
  EXPECT_EQ(result.counters.sets, 2u);

  // Level 2 (along z): two pass pairs, one per set, each fitted to its set alone.
  std::vector<const VisibilityCall*> level2;
  for (const auto& c : g.backend().log())
    if (c.kind == Kind::BeginPass && std::abs(c.view.direction.z()) == 1.0) level2.push_back(&c);
  ASSERT_EQ(level2.size(), 4u);
  EXPECT_EQ(level2[0]->depth, DepthUse::SharedFirst);
  EXPECT_EQ(level2[1]->depth, DepthUse::SharedSecond);
  EXPECT_EQ(level2[2]->depth, DepthUse::SharedFirst);
  EXPECT_EQ(level2[3]->depth, DepthUse::SharedSecond);
  const Aabb& first = level2[0]->view.bounds;
  const Aabb& second = level2[2]->view.bounds;
  EXPECT_TRUE(first.max().y() < second.min().y() || second.max().y() < first.min().y());
  expectObjectsDrawnAsGroups(g.backend());
}

TEST(OursOracle, SortedListsOfRecurringSetsAreKeptAcrossFrames) {
  auto s = twoPairs();
  testing::BoxGeometricOracle g;
  HierarchicalCollisionIndependentSets strategy(DetectorOptions{}, {0, withLeaves(2)});
  strategy.attach(s.scene, g.backend());
  (void)strategy.cull({s.poses, 0});
  EXPECT_EQ(strategy.lastFrame().listsKept, 0u);
  const auto built = strategy.lastFrame().listsBuilt;
  for (auto& p : s.poses) p.translation.x() += 0.01;
  (void)strategy.cull({s.poses, 1});
  EXPECT_EQ(strategy.lastFrame().listsKept, built);
  EXPECT_EQ(strategy.lastFrame().listsBuilt, 0u);
}

// ---- both, on random scenes decided from the geometry ---------------------------------------

struct TouchCheck {
  std::size_t touchingPairs = 0;
  std::size_t prunedTriangles = 0;
  std::size_t sets = 0;
};

// Every pair of triangles of two objects whose world AABBs overlap must be in one set, both
// triangles among their members'.
void expectNoTouchingTriangleLost(const SceneGeometry& scene, std::span<const Pose> poses,
                                  const CullingResult& result, TouchCheck& check) {
  const std::size_t n = scene.objectCount();
  std::vector<int> setOf(n, -1);
  std::vector<std::set<std::uint32_t>> kept(n);
  for (std::size_t k = 0; k < result.sets.size(); ++k) {
    EXPECT_GE(result.sets[k].members.size(), 2u);
    for (const auto& m : result.sets[k].members) {
      EXPECT_EQ(setOf[m.object], -1) << "object " << m.object << " in two sets";
      setOf[m.object] = static_cast<int>(k);
      if (m.allTriangles())
        for (std::uint32_t t = 0; t < scene.meshOf(m.object).triangleCount(); ++t)
          kept[m.object].insert(t);
      else
        kept[m.object].insert(m.triangles.begin(), m.triangles.end());
    }
  }
  check.sets += result.sets.size();
  std::vector<std::vector<Aabb>> boxes(n);
  for (ObjectId o = 0; o < n; ++o) {
    const Mesh& mesh = scene.meshOf(o);
    check.prunedTriangles += mesh.triangleCount() - kept[o].size();
    for (const auto& t : mesh.triangles) {
      Aabb b;
      for (std::uint32_t v : t) b.extend(poses[o].apply(mesh.vertices[v].cast<double>()));
      boxes[o].push_back(b);
    }
  }
  for (ObjectId a = 0; a < n; ++a)
    for (ObjectId b = a + 1; b < n; ++b)
      for (std::uint32_t ta = 0; ta < boxes[a].size(); ++ta)
        for (std::uint32_t tb = 0; tb < boxes[b].size(); ++tb) {
          if (!boxes[a][ta].intersects(boxes[b][tb])) continue;
          ++check.touchingPairs;
          EXPECT_TRUE(setOf[a] != -1 && setOf[a] == setOf[b])
              << "objects " << a << " and " << b << " split or pruned";
          EXPECT_TRUE(kept[a].count(ta) && kept[b].count(tb))
              << "triangles " << a << ":" << ta << " and " << b << ":" << tb << " pruned";
        }
}

template <class Strategy, class Options>
void checkRandomScenes() {
  TouchCheck check;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1.2, 1.2);
    std::normal_distribution<double> gauss;
    SceneGeometry scene;
    scene.meshes.push_back(makeTorus(0.5, 0.2, 6, 6));  // 72 triangles
    std::vector<Pose> poses;
    for (int i = 0; i < 10; ++i) {
      scene.objects.push_back({0, false, "torus"});
      Pose p;
      p.rotation = Eigen::Quaterniond(gauss(rng), gauss(rng), gauss(rng), gauss(rng)).normalized();
      p.translation = {u(rng), u(rng), u(rng)};
      poses.push_back(p);
    }
    testing::BoxGeometricOracle g;
    Options options;
    options.hierarchy = withLeaves(4);
    Strategy strategy(DetectorOptions{}, options);
    strategy.attach(scene, g.backend());
    for (int frame = 0; frame < 2; ++frame) {
      if (frame == 1)
        for (auto& p : poses) p.translation += Eigen::Vector3d(u(rng), u(rng), u(rng)) * 0.05;
      const auto result = strategy.cull({poses, frame});
      expectNoTouchingTriangleLost(scene, poses, result, check);
    }
  }
  // The scenes must touch, and the hierarchy must prune, for the test to mean anything.
  EXPECT_GT(check.touchingPairs, 0u);
  EXPECT_GT(check.prunedTriangles, 0u);
  EXPECT_GT(check.sets, 0u);
}

TEST(CullideBvhOracle, NeverLosesATouchingTrianglePairOnRandomTori) {
  checkRandomScenes<CullideWithHierarchy, CullideWithHierarchyOptions>();
}

TEST(OursOracle, NeverLosesATouchingTrianglePairOnRandomTori) {
  checkRandomScenes<HierarchicalCollisionIndependentSets, HierarchicalCisOptions>();
}

}  // namespace
}  // namespace cdb
