#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <vector>

#include "culling/exact/SweepAndPrune.h"

namespace cdb {
namespace {

// Closed boxes on a coarse grid, so that touching faces, edges and corners and exact duplicates
// are common; some boxes are flat or points.
std::vector<Aabb> randomBoxes(std::mt19937_64& rng, int count, int gridSize) {
  std::uniform_int_distribution<int> corner(0, gridSize), size(0, 3);
  std::vector<Aabb> boxes;
  for (int i = 0; i < count; ++i) {
    if (i > 0 && i % 7 == 0) {  // a duplicate of an earlier box
      boxes.push_back(boxes[std::uniform_int_distribution<int>(0, i - 1)(rng)]);
      continue;
    }
    const Eigen::Vector3d lo(corner(rng), corner(rng), corner(rng));
    const Eigen::Vector3d extent(size(rng), size(rng), size(rng));
    boxes.emplace_back(lo, lo + extent);
  }
  return boxes;
}

std::vector<IndexPair> bruteForce(const std::vector<Aabb>& boxes) {
  std::vector<IndexPair> out;
  for (std::uint32_t i = 0; i < boxes.size(); ++i)
    for (std::uint32_t j = i + 1; j < boxes.size(); ++j)
      if (boxes[i].intersects(boxes[j])) out.push_back({i, j});
  return out;
}

std::vector<IndexPair> bruteForce(const std::vector<Aabb>& a, const std::vector<Aabb>& b) {
  std::vector<IndexPair> out;
  for (std::uint32_t i = 0; i < a.size(); ++i)
    for (std::uint32_t j = 0; j < b.size(); ++j)
      if (a[i].intersects(b[j])) out.push_back({i, j});
  return out;
}

class SweepAndPruneRandom : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(SweepAndPruneRandom, MatchesBruteForceAmongOneSet) {
  std::mt19937_64 rng(GetParam());
  SweepAndPrune sap;  // reused across calls, as the exact phase does
  std::vector<IndexPair> found;
  for (int round = 0; round < 20; ++round) {
    const auto boxes = randomBoxes(rng, 5 + round * 10, 12 + round);
    sap.overlaps(boxes, found);
    const auto expected = bruteForce(boxes);
    ASSERT_EQ(found, expected) << "round " << round;
    ASSERT_EQ(sweepAndPrune(boxes), expected);
    if (round > 3) {
      EXPECT_FALSE(expected.empty());
    }
  }
}

TEST_P(SweepAndPruneRandom, MatchesBruteForceBetweenTwoSets) {
  std::mt19937_64 rng(GetParam() * 31 + 5);
  SweepAndPrune sap;
  std::vector<IndexPair> found;
  for (int round = 0; round < 20; ++round) {
    const auto a = randomBoxes(rng, 3 + round * 7, 10 + round);
    auto b = randomBoxes(rng, 2 + round * 5, 10 + round);
    if (!a.empty() && !b.empty()) b[0] = a[0];  // the same box on both sides
    sap.overlaps(a, b, found);
    std::sort(found.begin(), found.end());
    ASSERT_EQ(found, bruteForce(a, b)) << "round " << round;
  }
}

TEST_P(SweepAndPruneRandom, MatchesBruteForceBetweenTwoLargeSetsSweptPerCell) {
  // Enough small boxes on both sides for the grid of cells, on a lattice of quarters so that
  // boxes touch on cell borders too, plus a few boxes that span many cells and some outside the
  // common region.
  std::mt19937_64 rng(GetParam() * 7 + 1);
  std::uniform_int_distribution<int> corner(0, 40), size(0, 2), bigSize(8, 40);
  const auto lattice = [&](int count, int bigOnes, double shift) {
    std::vector<Aabb> boxes;
    for (int i = 0; i < count; ++i) {
      const bool big = i < bigOnes;
      const int x = corner(rng), y = corner(rng), z = corner(rng);
      const int w = big ? bigSize(rng) : size(rng), h = big ? bigSize(rng) : size(rng);
      const int d = big ? bigSize(rng) : size(rng);
      const Eigen::Vector3d lo = Eigen::Vector3d(x, y, z) * 0.25 + Eigen::Vector3d::Constant(shift);
      boxes.emplace_back(lo, lo + Eigen::Vector3d(w, h, d) * 0.25);
    }
    return boxes;
  };
  SweepAndPrune sap;
  std::vector<IndexPair> found;
  for (int round = 0; round < 4; ++round) {
    const int bigA = round % 2 == 0 ? 5 : 0, bigB = round < 2 ? 4 : 0;
    const auto a = lattice(2500, bigA, 0.0);
    const auto b = lattice(1800, bigB, round == 3 ? 2.0 : 0.0);
    sap.overlaps(a, b, found);
    std::sort(found.begin(), found.end());
    const auto expected = bruteForce(a, b);
    ASSERT_EQ(found, expected) << "round " << round;
    EXPECT_GT(expected.size(), 500u);
  }
}

INSTANTIATE_TEST_SUITE_P(Seeds, SweepAndPruneRandom, ::testing::Values(1u, 2u, 3u, 99u, 12345u));

TEST(SweepAndPrune, TouchingBoxesOverlap) {
  const std::vector<Aabb> boxes = {
      Aabb(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1)),
      Aabb(Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(2, 1, 1)),    // shares a face with 0
      Aabb(Eigen::Vector3d(2, 1, 1), Eigen::Vector3d(3, 2, 2)),    // shares a corner with 1
      Aabb(Eigen::Vector3d(3.5, 0, 0), Eigen::Vector3d(4, 1, 1)),  // apart
  };
  EXPECT_EQ(sweepAndPrune(boxes), (std::vector<IndexPair>{{0, 1}, {1, 2}}));
}

TEST(SweepAndPrune, EmptyAndNanBoxesOverlapNothing) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Aabb> boxes = {
      Aabb(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1)),
      Aabb(),  // empty
      Aabb(Eigen::Vector3d(nan, 0, 0), Eigen::Vector3d(1, 1, 1)),
      Aabb(Eigen::Vector3d(0.5, 0.5, 0.5), Eigen::Vector3d(0.5, 0.5, 0.5)),  // a point inside 0
  };
  EXPECT_EQ(sweepAndPrune(boxes), (std::vector<IndexPair>{{0, 3}}));
  EXPECT_TRUE(sweepAndPrune({}).empty());
  EXPECT_TRUE(sweepAndPrune(std::vector<Aabb>(1, boxes[0])).empty());
}

TEST(SweepAndPrune, ChainOfTouchingBoxesAlongZ) {
  // Spread along z only, so z is the sweep axis and x, y overlap for every pair.
  std::vector<Aabb> boxes;
  for (int i = 0; i < 50; ++i)
    boxes.emplace_back(Eigen::Vector3d(0, 0, 2.0 * i), Eigen::Vector3d(1, 1, 2.0 * i + 2.0));
  const auto pairs = sweepAndPrune(boxes);
  ASSERT_EQ(pairs.size(), 49u);
  for (std::uint32_t i = 0; i < 49; ++i) EXPECT_EQ(pairs[i], (IndexPair{i, i + 1}));
}

}  // namespace
}  // namespace cdb
