// Collision-independent sets (thesis 3.3, Algorithm 3.2) against the scripted oracle: the worked
// example of Figures 3.7-3.16 exactly, set boundaries at gaps, the choice of the view axis, and on
// random boxes decided from the geometry, no touching pair split or dropped.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "BoxScenes.h"
#include "GeometricOracle.h"
#include "culling/SortedIntervals.h"
#include "culling/strategies/CollisionIndependentSets.h"
#include "culling/visibility/ScriptedVisibilityOracle.h"
#include "tests/common/RandomCases.h"

namespace cdb {
namespace {

using testing::box;

// Thesis object O_k is object id k - 1.
constexpr ObjectId O(int k) { return static_cast<ObjectId>(k - 1); }

// Sets as sorted member lists, in output order.
std::vector<std::vector<ObjectId>> setsOf(const CullingResult& r) {
  std::vector<std::vector<ObjectId>> out;
  for (const auto& s : r.sets) {
    std::vector<ObjectId> ids;
    for (const auto& m : s.members) {
      EXPECT_TRUE(m.allTriangles());
      ids.push_back(m.object);
    }
    std::sort(ids.begin(), ids.end());
    out.push_back(ids);
  }
  return out;
}

// Figure 3.7 along z, looking along +z (far = larger z): unit squares in x, y; the intervals
// along z put the endpoints, far to near, in the thesis' order
//   e5 e8 e3 b5 b8 e4 b3 e2 b4 e1 e6 b2 e7 b6 b1 b7   at z = 15, 14, ..., 0.
testing::BoxScene figure37() {
  const double z[8][2] = {{1, 6}, {4, 8}, {9, 13}, {7, 10}, {12, 15}, {2, 5}, {0, 3}, {11, 14}};
  std::vector<Aabb> boxes;
  for (const auto& iz : z) boxes.push_back(box(0, 1, 0, 1, iz[0], iz[1]));
  return testing::boxScene(boxes);
}

TEST(CisOracle, Figure37IsLaidOutInTheThesisOrder) {
  auto s = figure37();
  WorldBounds bounds;
  bounds.attach(s.scene);
  bounds.update(s.poses);
  SortedIntervals sorted;
  const std::vector<ObjectId> ids = {0, 1, 2, 3, 4, 5, 6, 7};
  sorted.update(ids, bounds, Eigen::Vector3d::UnitZ());
  std::string farToNear;
  const auto list = sorted.endpoints();
  for (auto it = list.rbegin(); it != list.rend(); ++it) {
    if (!farToNear.empty()) farToNear += ' ';
    farToNear += it->isMax ? 'e' : 'b';
    farToNear += std::to_string(it->object + 1);
  }
  EXPECT_EQ(farToNear, "e5 e8 e3 b5 b8 e4 b3 e2 b4 e1 e6 b2 e7 b6 b1 b7");
}

TEST(CisOracle, WorkedExampleOfFigures37To316) {
  auto s = figure37();
  // Pass 1: O8, O4, O6, O7 not fully visible. Pass 2: O2, O3, O5 not fully visible, O1 visible.
  ScriptedVisibilityOracle oracle([](const VisibilityCall& q, auto) {
    const std::set<ObjectId> hidden1 = {O(8), O(4), O(6), O(7)};
    const std::set<ObjectId> hidden2 = {O(2), O(3), O(5)};
    return !(q.pass == 0 ? hidden1 : hidden2).count(q.object);
  });
  CollisionIndependentSets cis(DetectorOptions{}, CisOptions{2});
  cis.attach(s.scene, oracle);
  const auto result = cis.cull({s.poses, 0});

  // The visibility tests in the thesis' order.
  EXPECT_EQ(oracle.queriedObjects(0),
            (std::vector<ObjectId>{O(5), O(8), O(3), O(4), O(2), O(6), O(1), O(7)}));
  EXPECT_EQ(oracle.queriedObjects(1), (std::vector<ObjectId>{O(1), O(2), O(3), O(5)}));

  // CIS1 = {O5, O8}, CIS2 = {O3, O4}, CIS3 = {O2, O6, O7}; O1 pruned.
  EXPECT_EQ(setsOf(result), (std::vector<std::vector<ObjectId>>{
                                {O(5), O(8)}, {O(3), O(4)}, {O(2), O(6), O(7)}}));
  EXPECT_EQ(result.counters.sets, 3u);
  EXPECT_EQ(result.counters.pcsSize, 7u);
  EXPECT_EQ(result.counters.pcsTriangles, 7u * 12);
  EXPECT_EQ(cis.lastFrame().dropped, 1u);
  EXPECT_EQ(cis.lastFrame().singletons, 0u);
  EXPECT_EQ(cis.lastFrame().axis, 2);
  // Figure 3.15: SS1 at b8, SS2 at b4, SS3 at b7 (positions far to near).
  EXPECT_EQ(cis.lastFrame().separatingSurfaces, (std::vector<std::uint32_t>{4, 8, 15}));

  // Two passes, one depth clear, one fetch each; pass 2 looks from the other side and draws
  // every object near to far.
  std::vector<const VisibilityCall*> starts;
  std::vector<ObjectId> written2;
  for (const auto& c : oracle.log()) {
    if (c.kind == VisibilityCall::Kind::BeginPass) starts.push_back(&c);
    if (c.kind == VisibilityCall::Kind::WriteRange && c.pass == 1) written2.push_back(c.object);
  }
  ASSERT_EQ(starts.size(), 2u);
  EXPECT_EQ(starts[0]->view.direction, Eigen::Vector3d::UnitZ());
  EXPECT_EQ(starts[0]->depth, DepthUse::SharedFirst);
  EXPECT_EQ(starts[1]->view.direction, -Eigen::Vector3d::UnitZ());
  EXPECT_EQ(starts[1]->depth, DepthUse::SharedSecond);
  EXPECT_EQ(written2,
            (std::vector<ObjectId>{O(7), O(1), O(6), O(2), O(4), O(3), O(8), O(5)}));
  EXPECT_EQ(result.counters.visibility.depthClears, 1u);
  EXPECT_EQ(result.counters.visibility.fetches, 2u);
  EXPECT_EQ(result.counters.visibility.queries, 12u);
}

TEST(CisOracle, FullyVisibleInPassOneEverywhereLeavesNothingToTestInPassTwo) {
  auto s = figure37();
  ScriptedVisibilityOracle oracle([](const VisibilityCall&, auto) { return true; });
  CollisionIndependentSets cis(DetectorOptions{}, CisOptions{2});
  cis.attach(s.scene, oracle);
  const auto result = cis.cull({s.poses, 0});
  EXPECT_TRUE(result.sets.empty());
  EXPECT_EQ(oracle.queriedObjects(0).size(), 8u);
  EXPECT_TRUE(oracle.queriedObjects(1).empty());
  EXPECT_EQ(cis.lastFrame().dropped, 8u);
}

TEST(CisOracle, SetsEndAtGapsAlongTheAxisAndSingletonsAreDropped) {
  // Along z: {0, 1} overlap, {2, 3} overlap, 4 alone; nothing is ever fully visible.
  auto s = testing::boxScene({box(0, 1, 0, 1, 0, 2), box(0, 1, 0, 1, 1, 3), box(0, 1, 0, 1, 5, 7),
                              box(0, 1, 0, 1, 6, 8), box(0, 1, 0, 1, 10, 11)});
  ScriptedVisibilityOracle oracle([](const VisibilityCall&, auto) { return false; });
  CollisionIndependentSets cis(DetectorOptions{}, CisOptions{2});
  cis.attach(s.scene, oracle);
  const auto result = cis.cull({s.poses, 0});
  EXPECT_EQ(setsOf(result), (std::vector<std::vector<ObjectId>>{{2, 3}, {0, 1}}));
  EXPECT_EQ(cis.lastFrame().singletons, 1u);
  EXPECT_TRUE(oracle.queriedObjects(1).empty());  // every object is a member after pass 1
}

TEST(CisOracle, ViewAxisIsWhereTheCentresSpreadMostUnlessFixed) {
  std::vector<Aabb> boxes;
  for (int i = 0; i < 5; ++i) boxes.push_back(box(0.25 * i, 1 + 0.25 * i, 3 * i, 3 * i + 1, 0, 1));
  auto s = testing::boxScene(boxes);
  for (const std::optional<int> fixed : {std::optional<int>{}, std::optional<int>{0}}) {
    ScriptedVisibilityOracle oracle([](const VisibilityCall&, auto) { return true; });
    CollisionIndependentSets cis(DetectorOptions{}, CisOptions{fixed});
    cis.attach(s.scene, oracle);
    (void)cis.cull({s.poses, 0});
    const int expected = fixed.value_or(1);
    EXPECT_EQ(cis.lastFrame().axis, expected);
    ASSERT_FALSE(oracle.log().empty());
    EXPECT_EQ(oracle.log().front().view.direction, Eigen::Vector3d::Unit(expected));
  }
}

// Random boxes, decided from the geometry: every pair of touching boxes ends in one set; the sets
// are disjoint and have two members or more. The second frame moves the boxes a little.
TEST(CisOracle, NeverSplitsOrDropsATouchingPairOnRandomBoxes) {
  std::size_t touching = 0, severalSets = 0, dropped = 0;
  for (std::uint64_t seed = 1; seed <= test::randomCases(10u); ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    const std::vector<Aabb> boxes = testing::randomBoxes(rng, 24, 5.0);
    std::uniform_real_distribution<double> half(0.2, 0.8);  // the second frame's moves
    auto s = testing::boxScene(boxes);
    testing::GeometricOracle g(s.scene);
    CollisionIndependentSets cis(DetectorOptions{});
    cis.attach(s.scene, g.backend());
    std::vector<std::uint32_t> all(12);
    for (std::uint32_t t = 0; t < 12; ++t) all[t] = t;
    for (int frame = 0; frame < 2; ++frame) {
      if (frame == 1)
        for (auto& p : s.poses) p.translation += Eigen::Vector3d(half(rng), half(rng), half(rng)) * 0.25;
      const auto result = cis.cull({s.poses, frame});
      severalSets += result.sets.size() > 1;
      dropped += cis.lastFrame().dropped;
      std::vector<int> setOf(boxes.size(), -1);
      for (std::size_t k = 0; k < result.sets.size(); ++k) {
        EXPECT_GE(result.sets[k].members.size(), 2u);
        for (const auto& m : result.sets[k].members) {
          EXPECT_EQ(setOf[m.object], -1) << "object " << m.object << " in two sets";
          setOf[m.object] = static_cast<int>(k);
        }
      }
      for (ObjectId a = 0; a < boxes.size(); ++a)
        for (ObjectId b = a + 1; b < boxes.size(); ++b) {
          if (!g.pieceBox(a, all).intersects(g.pieceBox(b, all))) continue;
          ++touching;
          EXPECT_TRUE(setOf[a] != -1 && setOf[a] == setOf[b])
              << "frame " << frame << ": " << a << " and " << b << " touch";
        }
    }
  }
  // The scenes must have contacts, several sets and pruned objects for the test to mean anything.
  EXPECT_GT(touching, 0u);
  EXPECT_GT(severalSets, 0u);
  EXPECT_GT(dropped, 0u);
}

}  // namespace
}  // namespace cdb
