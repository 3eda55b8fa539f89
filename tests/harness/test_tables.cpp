#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "harness/CdTimeTables.h"
#include "harness/TruthComparison.h"

namespace cdb {
namespace {

FrameRecord row(std::string strategy, int res, int objects, double ms) {
  FrameRecord r;
  r.environment = "env3";
  r.strategy = std::move(strategy);
  r.resolution = res;
  r.objects = objects;
  r.cdMs = ms;
  r.sets = 2;
  return r;
}

TEST(CdTimeTables, AverageAndMaximumPerStrategyAndColumn) {
  const std::vector<FrameRecord> frames = {row("cullide", 800, 50, 1.0), row("cullide", 800, 50, 3.0),
                                           row("cullide", 800, 75, 5.0), row("ours", 800, 50, 0.5)};
  const auto cells = summariseCdTimes(frames);
  ASSERT_EQ(cells.size(), 3u);
  EXPECT_EQ(cells[0].strategy, "cullide");
  EXPECT_EQ(cells[0].objects, 50);
  EXPECT_DOUBLE_EQ(cells[0].averageMs, 2.0);
  EXPECT_DOUBLE_EQ(cells[0].maximumMs, 3.0);
  EXPECT_EQ(cells[0].frames, 2u);
  EXPECT_EQ(cells[1].objects, 75);
  EXPECT_EQ(cells[2].strategy, "ours");

  const std::string md = cdTimeTablesMarkdown(cells);
  // Object counts vary, so they are the columns (the shape of Table 4.3).
  EXPECT_NE(md.find("| strategy | 50 | 75 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| cullide | 2.0000 | 5.0000 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| ours | 0.5000 |  |"), std::string::npos) << md;
}

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
