#include <gtest/gtest.h>

#include <vector>

#include "TestScenes.h"
#include "culling/exact/GroundTruth.h"
#include "culling/exact/TriangleTriangle.h"

namespace cdb {
namespace {

// Every triangle of every object against every triangle of every other object.
CollisionReport bruteForce(const SceneGeometry& scene, const std::vector<Pose>& poses) {
  std::vector<std::vector<Eigen::Vector3d>> world;
  for (ObjectId o = 0; o < scene.objectCount(); ++o)
    world.push_back(testing::worldVertices(scene.meshOf(o), poses[o]));
  CollisionReport report;
  for (ObjectId a = 0; a < scene.objectCount(); ++a) {
    for (ObjectId b = a + 1; b < scene.objectCount(); ++b) {
      std::uint64_t hits = 0;
      for (const Triangle& x : scene.meshOf(a).triangles)
        for (const Triangle& y : scene.meshOf(b).triangles)
          hits += trianglesIntersect(world[a][x[0]], world[a][x[1]], world[a][x[2]], world[b][y[0]],
                                     world[b][y[1]], world[b][y[2]]);
      if (hits > 0) report.collidingPairs.push_back({a, b});
      report.collidingTrianglePairs += hits;
    }
  }
  return report;
}

TEST(GroundTruth, MatchesBruteForceOnSmallToriScenes) {
  for (std::uint64_t seed = 1; seed < 1 + testing::kRepeats; ++seed) {
    const auto s = testing::randomTori(8, 1.6, testing::kRepeats, seed, 12, 8);
    const GroundTruth truth(s.scene);
    for (const auto& poses : s.frames) {
      const CollisionReport expected = bruteForce(s.scene, poses);
      const CollisionReport got = truth.compute(poses);
      EXPECT_EQ(got.collidingPairs, expected.collidingPairs) << "seed " << seed;
      EXPECT_EQ(got.collidingTrianglePairs, expected.collidingTrianglePairs) << "seed " << seed;
      EXPECT_GE(expected.collidingPairs.size(), 3u) << "scene too sparse to test much";
      EXPECT_LE(got.triangleTests, 28u * 192u * 192u);
    }
  }
}

TEST(GroundTruth, MatchesBruteForceWithMixedMeshes) {
  auto s = testing::randomTori(6, 1.5, 4, 77, 10, 6);
  s.scene.meshes.push_back(testing::unitCube());
  s.scene.meshes.push_back(Mesh{"empty", {}, {}, {}});
  s.scene.objects.push_back({1, false, "cube"});
  s.scene.objects.push_back({1, true, "cube"});
  s.scene.objects.push_back({2, false, "empty"});
  std::mt19937_64 rng(5);
  for (auto& poses : s.frames)
    for (int k = 0; k < 3; ++k) poses.push_back(testing::randomPose(rng, 0.0, 1.0));
  const GroundTruth truth(s.scene);
  for (const auto& poses : s.frames) {
    const CollisionReport expected = bruteForce(s.scene, poses);
    const CollisionReport got = truth.compute(poses);
    EXPECT_EQ(got.collidingPairs, expected.collidingPairs);
    EXPECT_EQ(got.collidingTrianglePairs, expected.collidingTrianglePairs);
  }
}

TEST(GroundTruth, CubesSharingAFaceTouch) {
  const SceneGeometry scene = testing::unitCubes(3);
  std::vector<Pose> poses(3);
  poses[1].translation = {1, 0, 0};          // face to face with cube 0
  poses[2].translation = {2 + 1e-12, 0, 0};  // 1e-12 away from cube 1
  const GroundTruth truth(scene);
  const CollisionReport got = truth.compute(poses);
  EXPECT_EQ(got.collidingPairs, (std::vector<ObjectPair>{{0, 1}}));
  EXPECT_EQ(got.collidingTrianglePairs, bruteForce(scene, poses).collidingTrianglePairs);

  poses[2].translation = {2, 0.5, 0.5};  // now touching cube 1 on part of a face
  EXPECT_EQ(truth.compute(poses).collidingPairs, (std::vector<ObjectPair>{{0, 1}, {1, 2}}));
}

TEST(GroundTruth, RejectsTooFewPoses) {
  const auto s = testing::randomTori(3, 1.0, 1, 1, 6, 4);
  const GroundTruth truth(s.scene);
  EXPECT_THROW((void)truth.compute(std::vector<Pose>(2)), std::invalid_argument);
}

TEST(GroundTruth, IsMovable) {
  const auto s = testing::randomTori(5, 1.0, 1, 3, 8, 6);
  GroundTruth first(s.scene);
  const auto expected = first.compute(s.frames[0]).collidingPairs;
  GroundTruth moved(std::move(first));
  EXPECT_EQ(moved.compute(s.frames[0]).collidingPairs, expected);
}

}  // namespace
}  // namespace cdb
