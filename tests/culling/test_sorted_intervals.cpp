// The sorted endpoint list: order, ties, positions, and the exchanges of the incremental sort.
#include <gtest/gtest.h>

#include "BoxScenes.h"
#include "culling/SortedIntervals.h"

namespace cdb {
namespace {

using testing::box;

std::vector<ObjectId> idsUpTo(std::size_t n) {
  std::vector<ObjectId> ids(n);
  for (std::size_t i = 0; i < n; ++i) ids[i] = static_cast<ObjectId>(i);
  return ids;
}

// "b3" for the MIN of object 3, "e3" for its MAX, ascending.
std::vector<std::string> names(const SortedIntervals& s) {
  std::vector<std::string> out;
  for (const auto& e : s.endpoints()) {
    std::string name(1, e.isMax ? 'e' : 'b');
    name += std::to_string(e.object);
    out.push_back(name);
  }
  return out;
}

TEST(SortedIntervals, ProjectsBoxesOnEitherSignOfAnAxis) {
  const Aabb b = box(1, 2, -3, 5, 0, 4);
  EXPECT_EQ(projectAabb(b, Eigen::Vector3d::UnitY()), std::make_pair(-3.0, 5.0));
  EXPECT_EQ(projectAabb(b, -Eigen::Vector3d::UnitX()), std::make_pair(-2.0, -1.0));
}

TEST(SortedIntervals, AscendingWithMinBeforeMaxAtEqualValues) {
  auto s = testing::boxScene({box(2, 3, 0, 1, 0, 1), box(0, 2, 0, 1, 0, 1), box(-1, 0, 0, 1, 0, 1)});
  WorldBounds bounds;
  bounds.attach(s.scene);
  bounds.update(s.poses);
  SortedIntervals sorted;
  const auto ids = idsUpTo(3);
  sorted.update(ids, bounds, Eigen::Vector3d::UnitX());
  EXPECT_TRUE(sorted.lastUpdateRebuilt());
  // Touching intervals (2 touches 0 at x = 0, 1 touches 0 at x = 2) overlap: b before e.
  EXPECT_EQ(names(sorted), (std::vector<std::string>{"b2", "b1", "e2", "b0", "e1", "e0"}));
  EXPECT_EQ(sorted.minIndex(1), 1u);
  EXPECT_EQ(sorted.maxIndex(1), 4u);
  EXPECT_EQ(sorted.minIndex(0), 3u);
}

TEST(SortedIntervals, ResortsIncrementallyAndCountsExchanges) {
  auto s = testing::boxScene({box(0, 1, 0, 1, 0, 1), box(0.5, 1.5, 0, 1, 0, 1),
                              box(2, 3, 0, 1, 0, 1), box(4, 5, 0, 1, 0, 1)});
  WorldBounds bounds;
  bounds.attach(s.scene);
  bounds.update(s.poses);
  SortedIntervals sorted;
  const auto ids = idsUpTo(4);
  EXPECT_EQ(sorted.update(ids, bounds, Eigen::Vector3d::UnitX()), 0u);
  // Nothing moved: nothing exchanged, nothing rebuilt.
  EXPECT_EQ(sorted.update(ids, bounds, Eigen::Vector3d::UnitX()), 0u);
  EXPECT_FALSE(sorted.lastUpdateRebuilt());

  // Object 1 moves slightly left past object 0's ends: b1 passes b0, e1 passes e0.
  s.poses[1].translation.x() -= 0.625;
  bounds.update(s.poses);
  EXPECT_EQ(sorted.update(ids, bounds, Eigen::Vector3d::UnitX()), 2u);
  EXPECT_EQ(names(sorted),
            (std::vector<std::string>{"b1", "b0", "e1", "e0", "b2", "e2", "b3", "e3"}));

  // Everything mirrored: every pair of the 8 endpoints is exchanged except each object's own
  // b before e and, as objects 0 and 1 overlap, b0 before e1 and b1 before e0.
  for (auto& p : s.poses) p.translation.x() = -p.translation.x();
  bounds.update(s.poses);
  EXPECT_EQ(sorted.update(ids, bounds, Eigen::Vector3d::UnitX()), 8u * 7 / 2 - 4 - 2);
  EXPECT_EQ(names(sorted),
            (std::vector<std::string>{"b3", "e3", "b2", "e2", "b0", "b1", "e0", "e1"}));
}

TEST(SortedIntervals, RebuildsWhenTheObjectsChange) {
  auto s = testing::boxScene({box(0, 1, 0, 1, 0, 1), box(3, 4, 0, 1, 0, 1), box(1.5, 2, 0, 1, 0, 1)});
  WorldBounds bounds;
  bounds.attach(s.scene);
  bounds.update(s.poses);
  SortedIntervals sorted;
  const auto all = idsUpTo(3);
  sorted.update(all, bounds, Eigen::Vector3d::UnitX());
  const std::vector<ObjectId> some = {2, 1};
  EXPECT_EQ(sorted.update(some, bounds, Eigen::Vector3d::UnitX()), 0u);
  EXPECT_TRUE(sorted.lastUpdateRebuilt());
  EXPECT_EQ(sorted.objectCount(), 2u);
  EXPECT_EQ(names(sorted), (std::vector<std::string>{"b2", "e2", "b1", "e1"}));
  // Slots follow the order of the objects given.
  EXPECT_EQ(sorted.minIndex(0), 0u);
  EXPECT_EQ(sorted.minIndex(1), 2u);
}

}  // namespace
}  // namespace cdb
