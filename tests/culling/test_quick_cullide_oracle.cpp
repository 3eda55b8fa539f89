// Quick-CULLIDE's classification against the scripted oracle: the same passes as CULLIDE, pairs
// freed by one pass of one piece, the pairs and triangles it leaves for the exact phase; and on
// random boxes decided from the geometry, no pair it frees ever touches.
#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <random>
#include <set>

#include "BoxScenes.h"
#include "GeometricOracle.h"
#include "culling/exact/ExactPhase.h"
#include "culling/exact/GroundTruth.h"
#include "culling/strategies/Cullide.h"
#include "culling/strategies/QuickCullide.h"
#include "culling/visibility/ScriptedVisibilityOracle.h"
#include "scenes/ProceduralMeshes.h"
#include "tests/common/RandomCases.h"

namespace cdb {
namespace {

constexpr std::uint32_t kTorusTriangles = 32;

// Four small tori stacked so closely that every pair of world boxes overlaps: the exact phase's
// sweep keeps every pair a strategy leaves it.
SceneGeometry fourTori() {
  SceneGeometry s;
  s.meshes.push_back(makeTorus(0.5, 0.2, 4, 4));
  for (int i = 0; i < 4; ++i) s.objects.push_back({0, false, "torus"});
  return s;
}

std::vector<Pose> stackedPoses() {
  std::vector<Pose> poses(4);
  for (int i = 0; i < 4; ++i) poses[i].translation = {0.05 * i, 0.0, 0.0};
  return poses;
}

bool objectQuery(const VisibilityCall& q) { return q.range.triangleCount == kTorusTriangles; }
bool firstPass(const VisibilityCall& q) { return q.pass % 2 == 0; }

// Object level: 0, 1 and 2 are never fully visible; 3 (last in pass 1) is fully visible in pass 1
// only, so CULLIDE keeps it while each of its pairs is freed. Triangle level: 0 is fully visible
// in pass 1 and its even triangles in pass 2; 1's odd triangles in pass 1 and its triangles below
// 16 in pass 2; 2's triangles from 16 on in pass 1 and all of them in pass 2; none of 3's ever.
// No triangle of 0..2 is fully visible in both passes except 0's even ones, 1's odd ones below 16
// and 2's from 16 on, which CULLIDE prunes too.
bool scriptedAnswer(const VisibilityCall& q) {
  if (q.kind != VisibilityCall::Kind::QueryRange) return false;
  if (objectQuery(q)) return q.object == 3 && firstPass(q);
  const std::uint32_t t = q.range.firstTriangle;
  switch (q.object) {
    case 0: return firstPass(q) || t % 2 == 0;
    case 1: return firstPass(q) ? t % 2 == 1 : t < 16;
    case 2: return firstPass(q) ? t >= 16 : true;
    default: return false;
  }
}

std::vector<std::uint32_t> trianglesWhere(const std::function<bool(std::uint32_t)>& keep) {
  std::vector<std::uint32_t> out;
  for (std::uint32_t t = 0; t < kTorusTriangles; ++t)
    if (keep(t)) out.push_back(t);
  return out;
}

TEST(QuickCullideOracle, ClassificationFreesPairsThatCullidesPcsKeeps) {
  const auto scene = fourTori();
  const auto poses = stackedPoses();
  ScriptedVisibilityOracle forCullide([](const VisibilityCall& q, auto) { return scriptedAnswer(q); });
  ScriptedVisibilityOracle forQuick([](const VisibilityCall& q, auto) { return scriptedAnswer(q); });
  Cullide cullide(DetectorOptions{});
  cullide.attach(scene, forCullide);
  QuickCullide quick(DetectorOptions{});
  quick.attach(scene, forQuick);
  const auto byCullide = cullide.cull({poses, 0});
  const auto byQuick = quick.cull({poses, 0});

  // CULLIDE: one set of all four, every member pair swept.
  ASSERT_EQ(byCullide.sets.size(), 1u);
  const auto& pcs = byCullide.sets[0];
  ASSERT_EQ(pcs.members.size(), 4u);
  EXPECT_FALSE(pcs.pairs.has_value());
  EXPECT_EQ(pcs.members[0].triangles, trianglesWhere([](auto t) { return t % 2 == 1; }));
  EXPECT_EQ(pcs.members[1].triangles, trianglesWhere([](auto t) { return t % 2 == 0 || t >= 16; }));
  EXPECT_EQ(pcs.members[2].triangles, trianglesWhere([](auto t) { return t < 16; }));
  EXPECT_TRUE(pcs.members[3].allTriangles());

  // Quick-CULLIDE: 3 leaves (fully visible in pass 1 with respect to 0, 1 and 2); of 1, the even
  // triangles may meet 0 (pass 1 cleared the odd ones of everything before 1) and those from 16
  // on may meet 2 (pass 2 cleared those below 16 of everything after 1).
  ASSERT_EQ(byQuick.sets.size(), 1u);
  const auto& set = byQuick.sets[0];
  ASSERT_EQ(set.members.size(), 3u);
  for (std::uint32_t i = 0; i < 3; ++i) EXPECT_EQ(set.members[i].object, i);
  EXPECT_EQ(set.members[0].triangles, pcs.members[0].triangles);
  EXPECT_EQ(set.members[1].triangles, pcs.members[1].triangles);
  EXPECT_EQ(set.members[2].triangles, pcs.members[2].triangles);
  ASSERT_TRUE(set.pairs.has_value());
  ASSERT_EQ(set.pairs->size(), 3u);
  // Positions in member 1's list (evens below 16, then 16..31): evens are 0..7 and 8, 10, ..., 22.
  std::vector<std::uint32_t> evensOfOne, upperOfOne;
  for (std::uint32_t k = 0; k < 8; ++k) evensOfOne.push_back(k);
  for (std::uint32_t k = 8; k < 24; k += 2) evensOfOne.push_back(k);
  for (std::uint32_t k = 8; k < 24; ++k) upperOfOne.push_back(k);
  const auto& p = *set.pairs;
  EXPECT_EQ(p[0].first, 0u);
  EXPECT_EQ(p[0].second, 1u);
  EXPECT_TRUE(p[0].firstTriangles.empty());  // all of 0's odd triangles
  EXPECT_EQ(p[0].secondTriangles, evensOfOne);
  EXPECT_EQ(p[1].first, 0u);
  EXPECT_EQ(p[1].second, 2u);
  EXPECT_TRUE(p[1].firstTriangles.empty());
  EXPECT_TRUE(p[1].secondTriangles.empty());
  EXPECT_EQ(p[2].first, 1u);
  EXPECT_EQ(p[2].second, 2u);
  EXPECT_EQ(p[2].firstTriangles, upperOfOne);
  EXPECT_TRUE(p[2].secondTriangles.empty());
  EXPECT_EQ(byQuick.counters.pcsSize, 3u);
  EXPECT_EQ(byQuick.counters.sets, 1u);
  EXPECT_EQ(byQuick.counters.pcsTriangles, 16u + 24u + 16u);

  // The exact phase tests the 3 listed pairs instead of CULLIDE's 6, and fewer triangle pairs.
  ExactPhase exact(scene);
  const auto cullideReport = exact.run(poses, byCullide.sets);
  const auto quickReport = exact.run(poses, byQuick.sets);
  EXPECT_EQ(cullideReport.pairsTested, 6u);
  EXPECT_EQ(quickReport.pairsTested, 3u);
  EXPECT_LT(quickReport.triangleTests, cullideReport.triangleTests);
}

TEST(QuickCullideOracle, RunsCullidesPassesInCullidesOrder) {
  // Nothing fully visible: nothing is freed, so both draw the same pieces in the same passes,
  // except that quick_cullide tests an object (a member) in pass 1 only when it is the later one
  // of a pair and in pass 2 only when it is the earlier one (the answers it reads): the first is
  // never tested in pass 1, the last never in pass 2.
  const auto scene = fourTori();
  const auto poses = stackedPoses();
  ScriptedVisibilityOracle forCullide([](const VisibilityCall&, auto) { return false; });
  ScriptedVisibilityOracle forQuick([](const VisibilityCall&, auto) { return false; });
  Cullide cullide(DetectorOptions{});
  cullide.attach(scene, forCullide);
  QuickCullide quick(DetectorOptions{});
  quick.attach(scene, forQuick);
  (void)cullide.cull({poses, 0});
  const auto result = quick.cull({poses, 0});

  const std::vector<ObjectId> order = forCullide.queriedObjects(0);
  ASSERT_EQ(order.size(), 4u);
  std::vector<VisibilityCall> a;
  int omitted = 0;
  for (const VisibilityCall& c : forCullide.log()) {
    // (Passes 0-5 are the object level's, 6-11 the triangle level's, pass 1 and 2 in turn; the
    // oracle answers a batch one triangle at a time, a QueryRange each.)
    const bool pass1 = c.pass % 2 == 0;
    if (c.kind == VisibilityCall::Kind::QueryRange &&
        c.object == (pass1 ? order.front() : order.back())) {
      ++omitted;
      continue;
    }
    a.push_back(c);
  }
  EXPECT_EQ(omitted, 6 + 6 * static_cast<int>(scene.meshOf(0).triangleCount()))
      << "3 axes, one object and one member's triangles a pass";
  const auto& b = forQuick.log();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    SCOPED_TRACE("call " + std::to_string(k));
    EXPECT_EQ(a[k].kind, b[k].kind);
    EXPECT_EQ(a[k].pass, b[k].pass);
    EXPECT_EQ(a[k].object, b[k].object);
    EXPECT_EQ(a[k].range.firstTriangle, b[k].range.firstTriangle);
    EXPECT_EQ(a[k].range.triangleCount, b[k].range.triangleCount);
    EXPECT_EQ(a[k].view.direction, b[k].view.direction);
    EXPECT_EQ(a[k].depth, b[k].depth);
  }
  EXPECT_EQ(forQuick.counters().passes, 12u);
  ASSERT_EQ(result.sets.size(), 1u);
  EXPECT_EQ(result.sets[0].pairs->size(), 6u);
}

TEST(QuickCullideOracle, NothingLeftWhenEveryPieceIsFullyVisible) {
  const auto scene = fourTori();
  const auto poses = stackedPoses();
  ScriptedVisibilityOracle oracle([](const VisibilityCall&, auto) { return true; });
  QuickCullide quick(DetectorOptions{});
  quick.attach(scene, oracle);
  const auto result = quick.cull({poses, 0});
  EXPECT_TRUE(result.sets.empty());
  EXPECT_EQ(result.counters.pcsSize, 0u);
  EXPECT_EQ(result.counters.visibility.passes, 2u);
}

// Per listed pair (smaller object first), the mesh triangles of each side.
using SideTriangles = std::pair<std::set<std::uint32_t>, std::set<std::uint32_t>>;
std::map<ObjectPair, SideTriangles> listedTriangles(const CullingResult& r, const SceneGeometry& scene) {
  std::map<ObjectPair, SideTriangles> out;
  for (const auto& set : r.sets) {
    EXPECT_TRUE(set.pairs.has_value());
    if (!set.pairs) continue;
    const auto meshTriangles = [&](std::uint32_t member, const std::vector<std::uint32_t>& positions) {
      const SetMember& m = set.members[member];
      const auto count = static_cast<std::uint32_t>(scene.meshOf(m.object).triangleCount());
      std::set<std::uint32_t> tris;
      const auto add = [&](std::uint32_t k) { tris.insert(m.allTriangles() ? k : m.triangles.at(k)); };
      if (positions.empty()) {
        for (std::uint32_t k = 0; k < (m.allTriangles() ? count : m.triangles.size()); ++k) add(k);
      } else {
        for (std::uint32_t k : positions) add(k);
      }
      return tris;
    };
    for (const auto& p : *set.pairs) {
      auto a = meshTriangles(p.first, p.firstTriangles);
      auto b = meshTriangles(p.second, p.secondTriangles);
      const ObjectId oa = set.members[p.first].object, ob = set.members[p.second].object;
      EXPECT_NE(oa, ob);
      if (oa > ob) std::swap(a, b);
      EXPECT_TRUE(out.emplace(ObjectPair::of(oa, ob), SideTriangles{a, b}).second) << "listed twice";
    }
  }
  return out;
}

// Random boxes decided from the geometry (pieces whose boxes touch are never fully visible with
// respect to each other): every two triangles whose boxes touch stay on the two sides of a listed
// pair, so no pair the classification frees can collide; the exact phase then finds the ground
// truth's pairs, testing no more pairs than after CULLIDE, and over the seeds fewer pairs are
// left than CULLIDE's set holds.
TEST(QuickCullideOracle, NoFreedPairEverTouchesOnRandomBoxes) {
  std::size_t touching = 0;
  std::uint64_t listedPairs = 0, cullidePairs = 0, truthPairs = 0;
  for (std::uint64_t seed = 1; seed <= test::randomCases(10u); ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    const std::vector<Aabb> boxes = testing::randomBoxes(rng, 14, 4.0);
    auto s = testing::boxScene(boxes);
    testing::GeometricOracle forQuick(s.scene), forCullide(s.scene);
    QuickCullide quick(DetectorOptions{});
    quick.attach(s.scene, forQuick.backend());
    Cullide cullide(DetectorOptions{});
    cullide.attach(s.scene, forCullide.backend());
    const GroundTruth truth(s.scene);
    ExactPhase exact(s.scene);

    const auto result = quick.cull({s.poses, 0});
    const auto listed = listedTriangles(result, s.scene);
    for (ObjectId a = 0; a < boxes.size(); ++a)
      for (ObjectId b = a + 1; b < boxes.size(); ++b)
        for (std::uint32_t t = 0; t < 12; ++t)
          for (std::uint32_t u = 0; u < 12; ++u) {
            const std::uint32_t ta[] = {t}, ub[] = {u};
            if (!forQuick.pieceBox(a, ta).intersects(forQuick.pieceBox(b, ub))) continue;
            ++touching;
            const auto it = listed.find({a, b});
            ASSERT_NE(it, listed.end()) << "objects " << a << " and " << b << " touch but were freed";
            EXPECT_TRUE(it->second.first.count(t) && it->second.second.count(u))
                << "triangle " << t << " of " << a << " touches " << u << " of " << b;
          }

    const auto expected = truth.compute(s.poses).collidingPairs;
    const auto byQuick = exact.run(s.poses, result.sets);
    EXPECT_EQ(byQuick.collidingPairs, expected);
    const auto culled = cullide.cull({s.poses, 0});
    const auto byCullide = exact.run(s.poses, culled.sets);
    // With fewer pieces drawn, a geometric oracle answers "fully visible" at least as often, so
    // what Quick-CULLIDE leaves is inside what CULLIDE leaves.
    EXPECT_LE(byQuick.pairsTested, byCullide.pairsTested);
    EXPECT_LE(byQuick.triangleTests, byCullide.triangleTests);
    listedPairs += listed.size();
    for (const auto& set : culled.sets) cullidePairs += set.members.size() * (set.members.size() - 1) / 2;
    truthPairs += expected.size();
  }
  EXPECT_GT(touching, 0u);
  EXPECT_GT(truthPairs, 0u);
  EXPECT_LT(listedPairs, cullidePairs);
}

}  // namespace
}  // namespace cdb
