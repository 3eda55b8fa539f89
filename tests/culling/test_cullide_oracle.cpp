// CULLIDE's control flow against the scripted oracle: pass order, axes, pruning rule.
#include <gtest/gtest.h>

#include "culling/strategies/Cullide.h"
#include "culling/visibility/ScriptedVisibilityOracle.h"
#include "scenes/ProceduralMeshes.h"

namespace cdb {
namespace {

SceneGeometry threeTori() {
  SceneGeometry s;
  s.meshes.push_back(makeTorus(0.5, 0.2, 4, 4));  // 32 triangles
  for (int i = 0; i < 3; ++i) s.objects.push_back({0, false, "torus"});
  return s;
}

std::vector<Pose> spreadPoses() {
  std::vector<Pose> poses(3);
  for (int i = 0; i < 3; ++i) poses[i].translation = {2.0 * i, 0, 0};
  return poses;
}

TEST(CullideOracle, EverythingFullyVisibleEmptiesThePcsAfterTheFirstAxis) {
  const auto scene = threeTori();
  const auto poses = spreadPoses();
  ScriptedVisibilityOracle oracle([](const VisibilityCall&, auto) { return true; });
  Cullide cullide(DetectorOptions{});
  cullide.attach(scene, oracle);
  const auto result = cullide.cull({poses, 0});
  EXPECT_TRUE(result.sets.empty());
  EXPECT_EQ(result.counters.pcsSize, 0u);
  // One axis at object level: pass 1 in order, pass 2 in reverse, then nothing left to test.
  EXPECT_EQ(oracle.queriedObjects(0), (std::vector<ObjectId>{0, 1, 2}));
  EXPECT_EQ(oracle.queriedObjects(1), (std::vector<ObjectId>{2, 1, 0}));
  EXPECT_TRUE(oracle.queriedObjects(2).empty());
  EXPECT_EQ(result.counters.visibility.queries, 6u);
  EXPECT_EQ(result.counters.visibility.passes, 2u);
}

TEST(CullideOracle, NothingVisibleKeepsEveryObjectAndTriangleThroughAllAxesAndLevels) {
  const auto scene = threeTori();
  const auto poses = spreadPoses();
  ScriptedVisibilityOracle oracle([](const VisibilityCall&, auto) { return false; });
  Cullide cullide(DetectorOptions{});
  cullide.attach(scene, oracle);
  const auto result = cullide.cull({poses, 0});
  ASSERT_EQ(result.sets.size(), 1u);
  ASSERT_EQ(result.sets[0].members.size(), 3u);
  for (const auto& m : result.sets[0].members) EXPECT_TRUE(m.allTriangles());
  // 3 axes x 2 passes at object level, then 3 axes x 2 passes at triangle level.
  EXPECT_EQ(result.counters.visibility.passes, 12u);
  EXPECT_EQ(result.counters.visibility.queries, 3u * 6 + 3u * 32 * 6);
  // Views along x, y, z in that order.
  std::vector<Eigen::Vector3d> directions;
  for (const auto& c : oracle.log())
    if (c.kind == VisibilityCall::Kind::BeginPass) directions.push_back(c.view.direction);
  ASSERT_EQ(directions.size(), 12u);
  EXPECT_EQ(directions[0], Eigen::Vector3d::UnitX());
  EXPECT_EQ(directions[2], Eigen::Vector3d::UnitY());
  EXPECT_EQ(directions[4], Eigen::Vector3d::UnitZ());
}

TEST(CullideOracle, AnObjectIsPrunedOnlyWhenFullyVisibleInBothPasses) {
  const auto scene = threeTori();
  const auto poses = spreadPoses();
  // Object 0 hidden in pass 1 only, object 1 visible in both, object 2 hidden in pass 2 only.
  ScriptedVisibilityOracle oracle([](const VisibilityCall& q, auto) {
    if (q.kind != VisibilityCall::Kind::QueryRange || q.range.triangleCount == 1) return false;
    const int passInAxis = q.pass % 2;
    if (q.object == 0) return passInAxis == 1;
    if (q.object == 2) return passInAxis == 0;
    return true;
  });
  Cullide cullide(DetectorOptions{});
  cullide.attach(scene, oracle);
  const auto result = cullide.cull({poses, 0});
  ASSERT_EQ(result.sets.size(), 1u);
  std::vector<ObjectId> kept;
  for (const auto& m : result.sets[0].members) kept.push_back(m.object);
  EXPECT_EQ(kept, (std::vector<ObjectId>{0, 2}));
}

TEST(CullideOracle, TrianglesVisibleInBothPassesLeaveTheSet) {
  const auto scene = threeTori();
  const auto poses = spreadPoses();
  // Objects never pruned; at triangle level only even triangles of object 1 stay hidden.
  ScriptedVisibilityOracle oracle([](const VisibilityCall& q, auto) {
    if (q.range.triangleCount != 1) return false;
    return !(q.object == 1 && q.range.firstTriangle % 2 == 0);
  });
  Cullide cullide(DetectorOptions{});
  cullide.attach(scene, oracle);
  const auto result = cullide.cull({poses, 0});
  // Objects 0 and 2 lose all their triangles in the first triangle-level axis; object 1 is then
  // alone, and an object alone collides with nothing.
  EXPECT_TRUE(result.sets.empty());
}

}  // namespace
}  // namespace cdb
