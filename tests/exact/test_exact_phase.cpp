#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "TestScenes.h"
#include "core/Aabb.h"
#include "culling/exact/ExactPhase.h"
#include "culling/exact/GroundTruth.h"

namespace cdb {
namespace {

PotentiallyCollidingSets oneSetOfAll(std::size_t objects) {
  PotentiallyCollidingSets sets(1);
  for (ObjectId o = 0; o < objects; ++o) sets[0].members.push_back({o, {}});
  return sets;
}

std::vector<Aabb> worldBoxes(const SceneGeometry& scene, const std::vector<Pose>& poses) {
  std::vector<Aabb> boxes;
  for (ObjectId o = 0; o < scene.objectCount(); ++o)
    boxes.push_back(transformAabb(scene.meshOf(o).bounds(), poses[o]));
  return boxes;
}

// Connected components of the (slightly widened) world-box overlap graph: a valid partition, as
// no two objects of different components can touch.
PotentiallyCollidingSets overlapComponents(const SceneGeometry& scene,
                                           const std::vector<Pose>& poses) {
  auto boxes = worldBoxes(scene, poses);
  for (auto& b : boxes)
    b.extend(b.min() - Eigen::Vector3d::Constant(1e-6))
        .extend(b.max() + Eigen::Vector3d::Constant(1e-6));
  std::vector<ObjectId> parent(scene.objectCount());
  std::iota(parent.begin(), parent.end(), 0u);
  const auto root = [&](ObjectId x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (ObjectId a = 0; a < boxes.size(); ++a)
    for (ObjectId b = a + 1; b < boxes.size(); ++b)
      if (boxes[a].intersects(boxes[b])) parent[root(a)] = root(b);
  PotentiallyCollidingSets sets;
  std::vector<int> setOf(scene.objectCount(), -1);
  for (ObjectId o = 0; o < scene.objectCount(); ++o) {
    const ObjectId r = root(o);
    if (setOf[r] < 0) {
      setOf[r] = int(sets.size());
      sets.emplace_back();
    }
    sets[setOf[r]].members.push_back({o, {}});
  }
  return sets;
}

TEST(ExactPhase, MatchesGroundTruthWithOneSetOfAllTori) {
  for (std::uint64_t seed = 11; seed < 11 + testing::kRepeats; ++seed) {
    const auto s = testing::randomTori(60, 3.0, testing::kRepeats, seed);
    const GroundTruth truth(s.scene);
    ExactPhase exact(s.scene);  // one instance over all frames: buffers are reused
    const auto sets = oneSetOfAll(s.scene.objectCount());
    for (const auto& poses : s.frames) {
      const CollisionReport expected = truth.compute(poses);
      const CollisionReport got = exact.run(poses, sets);
      EXPECT_EQ(got.collidingPairs, expected.collidingPairs) << "seed " << seed;
      EXPECT_EQ(got.collidingTrianglePairs, expected.collidingTrianglePairs) << "seed " << seed;
      EXPECT_GE(expected.collidingPairs.size(), 40u) << "scene too sparse to test much";
      EXPECT_GE(got.pairsTested, got.collidingPairs.size());
      EXPECT_GE(got.triangleTests, got.collidingTrianglePairs);
    }
  }
}

TEST(ExactPhase, MatchesGroundTruthWithSetsFromBoxOverlap) {
  const auto s = testing::randomTori(80, 8.0, testing::kRepeats, 21);
  const GroundTruth truth(s.scene);
  ExactPhase exact(s.scene);
  for (const auto& poses : s.frames) {
    const auto sets = overlapComponents(s.scene, poses);
    EXPECT_GT(sets.size(), 1u);
    const CollisionReport expected = truth.compute(poses);
    const CollisionReport got = exact.run(poses, sets);
    EXPECT_EQ(got.collidingPairs, expected.collidingPairs);
    EXPECT_EQ(got.collidingTrianglePairs, expected.collidingTrianglePairs);
    EXPECT_FALSE(expected.collidingPairs.empty());
  }
}

TEST(ExactPhase, MatchesGroundTruthWithTriangleSubsets) {
  // Each member keeps only the triangles whose world box reaches another object's box: a valid
  // restriction, so nothing may be lost. Small and large subsets take different paths.
  const auto s = testing::randomTori(50, 3.0, testing::kRepeats, 31);
  const GroundTruth truth(s.scene);
  ExactPhase exact(s.scene);
  for (const auto& poses : s.frames) {
    const auto boxes = worldBoxes(s.scene, poses);
    PotentiallyCollidingSets sets(1);
    std::size_t kept = 0, total = 0;
    for (ObjectId o = 0; o < s.scene.objectCount(); ++o) {
      const Mesh& mesh = s.scene.meshOf(o);
      const auto world = testing::worldVertices(mesh, poses[o]);
      SetMember member{o, {}};
      for (std::uint32_t t = 0; t < mesh.triangleCount(); ++t) {
        Aabb box(world[mesh.triangles[t][0]]);
        box.extend(world[mesh.triangles[t][1]]).extend(world[mesh.triangles[t][2]]);
        box.min().array() -= 1e-9;
        box.max().array() += 1e-9;
        for (ObjectId other = 0; other < s.scene.objectCount(); ++other) {
          if (other != o && box.intersects(boxes[other])) {
            member.triangles.push_back(t);
            break;
          }
        }
      }
      if (member.triangles.empty()) continue;  // touches nothing: pruned
      kept += member.triangles.size();
      total += mesh.triangleCount();
      sets[0].members.push_back(std::move(member));
    }
    EXPECT_LT(kept, total);
    const CollisionReport expected = truth.compute(poses);
    const CollisionReport got = exact.run(poses, sets);
    EXPECT_EQ(got.collidingPairs, expected.collidingPairs);
    EXPECT_EQ(got.collidingTrianglePairs, expected.collidingTrianglePairs);
  }
}

TEST(ExactPhase, SmallSubsetFindsItsCollision) {
  // One triangle of each cube, the two faces touching: the few-triangle path.
  const SceneGeometry scene = testing::unitCubes(2);
  std::vector<Pose> poses(2);
  poses[1].translation = {1, 0.25, 0.25};
  ExactPhase exact(scene);
  PotentiallyCollidingSets sets(1);
  sets[0].members = {{0, {10, 11}},
                     {1, {8}}};  // cube 0's +x face, one triangle of cube 1's -x face
  const CollisionReport got = exact.run(poses, sets);
  EXPECT_EQ(got.collidingPairs, (std::vector<ObjectPair>{{0, 1}}));
  EXPECT_GT(got.collidingTrianglePairs, 0u);
  sets[0].members[1].triangles = {2};  // a triangle of cube 1's top face, above cube 0
  EXPECT_TRUE(exact.run(poses, sets).collidingPairs.empty());
}

TEST(ExactPhase, PairInSeveralSetsIsReportedOnce) {
  const auto s = testing::randomTori(30, 2.5, 1, 41);
  const auto& poses = s.frames[0];
  ExactPhase exact(s.scene);
  const auto all = oneSetOfAll(s.scene.objectCount());
  const CollisionReport once = exact.run(poses, all);
  ASSERT_FALSE(once.collidingPairs.empty());
  PotentiallyCollidingSets twice = all;
  twice.push_back(all[0]);
  for (const ObjectPair& p : once.collidingPairs) twice.push_back({{{p.a, {}}, {p.b, {}}}});
  const CollisionReport got = exact.run(poses, twice);
  EXPECT_EQ(got.collidingPairs, once.collidingPairs);
  EXPECT_EQ(got.collidingTrianglePairs, once.collidingTrianglePairs);
  // Pairs already found colliding are not tested again; the others are, as a later set may hold
  // other triangles of them.
  EXPECT_EQ(got.pairsTested, 2 * once.pairsTested - once.collidingPairs.size());
}

TEST(ExactPhase, ThreadsChangeNothingItFindsOrCounts) {
  // Sets that exercise every skip: a pair in several sets, members sharing an object inside one
  // set (each object split in two halves), listed pairs. Reports must be equal at any thread count.
  const auto s = testing::randomTori(40, 2.5, testing::kRepeats, 53);
  std::vector<ExactPhase> phases;
  for (const int threads : {1, 2, 4}) phases.emplace_back(s.scene, threads);
  std::size_t colliding = 0;
  for (const auto& poses : s.frames) {
    const auto all = oneSetOfAll(s.scene.objectCount());
    PotentiallyCollidingSet halves;
    for (ObjectId o = 0; o < s.scene.objectCount(); ++o) {
      const std::uint32_t n = static_cast<std::uint32_t>(s.scene.meshOf(o).triangleCount());
      for (const std::uint32_t part : {0u, 1u}) {
        SetMember member{o, {}};
        for (std::uint32_t t = part * n / 2; t < (part + 1) * n / 2; ++t)
          member.triangles.push_back(t);
        halves.members.push_back(std::move(member));
      }
    }
    PotentiallyCollidingSets sets{halves};
    for (PotentiallyCollidingSet& set : overlapComponents(s.scene, poses)) sets.push_back(set);
    sets.push_back(all[0]);
    PotentiallyCollidingSet listed = all[0];
    listed.pairs = std::vector<MemberPair>{};
    for (std::uint32_t a = 0; a + 1 < listed.members.size(); a += 2)
      listed.pairs->push_back({a, a + 1, {}, {}});
    sets.push_back(listed);

    const CollisionReport one = phases[0].run(poses, sets);
    colliding += one.collidingPairs.size();
    for (std::size_t k = 1; k < phases.size(); ++k) {
      const CollisionReport got = phases[k].run(poses, sets);
      EXPECT_EQ(got.collidingPairs, one.collidingPairs);
      EXPECT_EQ(got.collidingTrianglePairs, one.collidingTrianglePairs);
      EXPECT_EQ(got.pairsTested, one.pairsTested);
      EXPECT_EQ(got.triangleTests, one.triangleTests);
    }
  }
  EXPECT_GT(colliding, 0u);
}

TEST(ExactPhase, AfterACollisionLaterMembersOfTheSameObjectsAreSkipped) {
  // Cube 0 twice in one set, overlapping cube 1: once (0, 1) is found, the second member of cube 0
  // is not tested against cube 1 again (with several sets, as then found pairs are remembered).
  const SceneGeometry scene = testing::unitCubes(3);
  std::vector<Pose> poses(3);
  poses[1].translation = {0.5, 0.25, 0};
  poses[2].translation = {5, 0, 0};
  const PotentiallyCollidingSets sets{{{{0, {}}, {0, {}}, {1, {}}}}, {{{2, {}}}}};
  for (const int threads : {1, 2}) {
    ExactPhase exact(scene, threads);
    const CollisionReport got = exact.run(poses, sets);
    EXPECT_EQ(got.collidingPairs, (std::vector<ObjectPair>{{0, 1}}));
    EXPECT_EQ(got.pairsTested, 1u) << threads << " threads";
  }
}

TEST(ExactPhase, CubesSharingAFaceTouch) {
  const SceneGeometry scene = testing::unitCubes(3);
  std::vector<Pose> poses(3);
  poses[1].translation = {1, 0, 0};          // face to face with cube 0: their boxes only touch
  poses[2].translation = {2 + 1e-12, 0, 0};  // 1e-12 away from cube 1
  ExactPhase exact(scene);
  const GroundTruth truth(scene);
  CollisionReport got = exact.run(poses, oneSetOfAll(3));
  EXPECT_EQ(got.collidingPairs, (std::vector<ObjectPair>{{0, 1}}));
  EXPECT_EQ(got.collidingTrianglePairs, truth.compute(poses).collidingTrianglePairs);

  // Rotated, the shared face is rounded differently on each side; both must still agree.
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  for (std::size_t i = 0; i < poses.size(); ++i) {
    poses[i].rotation = turn;
    poses[i].translation = turn * Eigen::Vector3d(double(i), 0, 0);
  }
  got = exact.run(poses, oneSetOfAll(3));
  const CollisionReport expected = truth.compute(poses);
  EXPECT_EQ(got.collidingPairs, expected.collidingPairs);
  EXPECT_EQ(got.collidingTrianglePairs, expected.collidingTrianglePairs);
}

TEST(ExactPhase, ListedPairsAreTheOnlyOnesTested) {
  const auto s = testing::randomTori(30, 2.5, 1, 41);
  const auto& poses = s.frames[0];
  ExactPhase exact(s.scene);
  auto sets = oneSetOfAll(s.scene.objectCount());
  const CollisionReport all = exact.run(poses, sets);
  ASSERT_GE(all.collidingPairs.size(), 2u);

  // Only the first colliding pair listed: the others are neither tested nor found.
  const ObjectPair listed = all.collidingPairs.front();
  sets[0].pairs = std::vector<MemberPair>{{listed.a, listed.b, {}, {}}};
  CollisionReport got = exact.run(poses, sets);
  EXPECT_EQ(got.collidingPairs, (std::vector<ObjectPair>{listed}));
  EXPECT_EQ(got.pairsTested, 1u);

  // Every overlapping pair listed: the sweep's answer.
  sets[0].pairs->clear();
  for (ObjectId a = 0; a < s.scene.objectCount(); ++a)
    for (ObjectId b = a + 1; b < s.scene.objectCount(); ++b) sets[0].pairs->push_back({a, b, {}, {}});
  got = exact.run(poses, sets);
  EXPECT_EQ(got.collidingPairs, all.collidingPairs);
  EXPECT_EQ(got.pairsTested, all.pairsTested);
  EXPECT_EQ(got.triangleTests, all.triangleTests);

  // No pair listed: nothing tested.
  sets[0].pairs->clear();
  got = exact.run(poses, sets);
  EXPECT_TRUE(got.collidingPairs.empty());
  EXPECT_EQ(got.pairsTested, 0u);
}

TEST(ExactPhase, ListedPairSidesRestrictTheTriangles) {
  // Cube 0's +x face touches cube 1's -x face; cube 1's top face is above cube 0.
  const SceneGeometry scene = testing::unitCubes(2);
  std::vector<Pose> poses(2);
  poses[1].translation = {1, 0.25, 0.25};
  ExactPhase exact(scene);
  PotentiallyCollidingSets sets(1);
  // Member 1 keeps triangles 2 (top face) and 8 (-x face); positions 0 and 1 of its list.
  sets[0].members = {{0, {10, 11}}, {1, {2, 8}}};
  sets[0].pairs = std::vector<MemberPair>{{0, 1, {}, {1}}};
  EXPECT_EQ(exact.run(poses, sets).collidingPairs, (std::vector<ObjectPair>{{0, 1}}));
  (*sets[0].pairs)[0].secondTriangles = {0};  // only the top face's triangle on member 1's side
  EXPECT_TRUE(exact.run(poses, sets).collidingPairs.empty());
  (*sets[0].pairs)[0].secondTriangles = {2};  // beyond member 1's two triangles
  EXPECT_THROW((void)exact.run(poses, sets), std::out_of_range);
  (*sets[0].pairs)[0] = {0, 2, {}, {}};  // no member 2
  EXPECT_THROW((void)exact.run(poses, sets), std::out_of_range);
}

TEST(ExactPhase, TrivialAndInvalidInput) {
  const auto s = testing::randomTori(4, 1.0, 1, 51, 8, 6);
  ExactPhase exact(s.scene);
  const auto& poses = s.frames[0];
  EXPECT_TRUE(exact.run(poses, {}).collidingPairs.empty());
  PotentiallyCollidingSets single(1);
  single[0].members.push_back({0, {}});
  const CollisionReport lone = exact.run(poses, single);
  EXPECT_TRUE(lone.collidingPairs.empty());
  EXPECT_EQ(lone.pairsTested, 0u);
  EXPECT_THROW((void)exact.run(std::vector<Pose>(3), oneSetOfAll(4)), std::invalid_argument);
  PotentiallyCollidingSets badTriangle(1);
  badTriangle[0].members = {{0, {100000}}, {1, {}}};
  EXPECT_THROW((void)exact.run(poses, badTriangle), std::out_of_range);
}

}  // namespace
}  // namespace cdb
