#include <gtest/gtest.h>

#include "harness/measure/TruthComparison.h"

namespace cdb {
namespace {

TEST(TruthComparison, CountsMissesSplitsAndExtras) {
  const std::vector<ObjectPair> truth = {{0, 1}, {2, 3}, {4, 5}};
  const std::vector<ObjectPair> found = {{0, 1}, {1, 2}};
  PotentiallyCollidingSets sets(2);
  sets[0].members = {{0, {}}, {1, {}}, {2, {}}};
  sets[1].members = {{3, {}}};  // 2 and 3 split across sets; 4 and 5 pruned
  const auto c = compareWithTruth(truth, found, sets, 6);
  EXPECT_EQ(c.falseNegatives, 2u);
  EXPECT_EQ(c.falsePositives, 1u);
  EXPECT_EQ(c.cullingMisses, 2u);
}

TEST(TruthComparison, ASetThatListsItsPairsHoldsOnlyThosePairsTogether) {
  const std::vector<ObjectPair> truth = {{0, 1}, {1, 2}, {2, 3}};
  PotentiallyCollidingSets sets(2);
  // Members 0, 1, 2 of objects 2, 1, 0: pairs {1, 2} and {0, 2} listed, {0, 1} freed.
  sets[0].members = {{2, {}}, {1, {}}, {0, {}}};
  sets[0].pairs = std::vector<MemberPair>{{1, 0, {}, {}}, {2, 0, {}, {}}};
  sets[1].members = {{2, {}}, {3, {}}};  // an ordinary set: 2 and 3 together
  const auto c = compareWithTruth(truth, truth, sets, 4);
  EXPECT_EQ(c.falseNegatives, 0u);
  EXPECT_EQ(c.cullingMisses, 1u);  // {0, 1}: both in the first set, but not listed there
}

TEST(TruthComparison, ADetectorThatCullsNothingMissesInCullingWhatItMisses) {
  const std::vector<ObjectPair> truth = {{0, 1}, {2, 3}, {4, 5}};
  DetectedFrame peer;
  peer.report.collidingPairs = {{0, 1}};
  const auto c = compareWithTruth(truth, peer, 6);
  EXPECT_EQ(c.falseNegatives, 2u);
  EXPECT_EQ(c.cullingMisses, 2u);  // no sets: without the rule, every truth pair would count

  DetectedFrame imageBased;
  imageBased.report.collidingPairs = {{0, 1}};
  imageBased.culled.emplace();
  imageBased.culled->sets.resize(1);
  imageBased.culled->sets[0].members = {{0, {}}, {1, {}}, {2, {}}, {3, {}}, {4, {}}, {5, {}}};
  const auto d = compareWithTruth(truth, imageBased, 6);
  EXPECT_EQ(d.falseNegatives, 2u);
  EXPECT_EQ(d.cullingMisses, 0u);  // every pair was left together for the exact phase
}

}  // namespace
}  // namespace cdb
