// How a run's cells are split into shares: every cell in exactly one share, and shares started
// together begin with different simulation groups.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "harness/run/RunPlan.h"

namespace {

cdb::ScenarioConfig sweep(int repeats, std::vector<int> counts) {
  cdb::ScenarioConfig config;
  config.sweep.repeats = repeats;
  config.sweep.objectCounts = std::move(counts);
  config.sweep.strategies = {"cullide", "cullide_bvh", "quick_cullide", "ours"};
  config.sweep.resolutions = {500, 600, 700, 800, 900, 1000, 1100, 1200};
  return config;
}

std::size_t groupIndex(const std::vector<cdb::Cell>& plan, const cdb::Cell& cell) {
  std::size_t group = 0;
  for (std::size_t k = 0; k < plan.size(); ++k) {
    if (k > 0 && !plan[k].sameFrames(plan[k - 1])) ++group;
    if (plan[k].key() == cell.key()) return group;
  }
  ADD_FAILURE() << cell.key() << " is not in the plan";
  return 0;
}

struct SplitCase {
  std::string name;
  int repeats;
  std::vector<int> counts;
  int shares;
};

class ShareSplit : public ::testing::TestWithParam<SplitCase> {};

TEST_P(ShareSplit, EveryCellOnceInTheShareTheDealGivesIt) {
  const auto& c = GetParam();
  const auto plan = cdb::planCells(sweep(c.repeats, c.counts));
  std::multiset<std::string> seen;
  for (int i = 1; i <= c.shares; ++i) {
    const auto share = cdb::shareOf(plan, {i, c.shares});
    // Back and forth, turned at each group: the share holds exactly the cells k of group g (k
    // counted from the group's first cell, p its place in its run of n) with (p + g) mod n = i - 1.
    const auto n = static_cast<std::size_t>(c.shares);
    std::set<std::string> expected;
    for (std::size_t k = 0, start = 0, group = 0; k < plan.size(); ++k) {
      if (k > 0 && !plan[k].sameFrames(plan[k - 1])) start = k, ++group;
      const std::size_t inGroup = k - start;
      const std::size_t place = (inGroup / n) % 2 == 0 ? inGroup % n : n - 1 - inGroup % n;
      if ((place + group) % n == static_cast<std::size_t>(i - 1)) expected.insert(plan[k].key());
    }
    std::set<std::string> got;
    for (const auto& cell : share) got.insert(cell.key()), seen.insert(cell.key());
    EXPECT_EQ(got, expected) << "share " << i;
  }
  EXPECT_EQ(seen.size(), plan.size());
  for (const auto& cell : plan) EXPECT_EQ(seen.count(cell.key()), 1u) << cell.key();
}

TEST_P(ShareSplit, SharesStartAtGroupsSpreadOverThePlanAndKeepGroupsTogether) {
  const auto& c = GetParam();
  const auto plan = cdb::planCells(sweep(c.repeats, c.counts));
  const std::size_t groups =
      static_cast<std::size_t>(c.repeats) * std::max<std::size_t>(1, c.counts.size());
  std::set<std::size_t> firstGroups;
  for (int i = 1; i <= c.shares; ++i) {
    const auto share = cdb::shareOf(plan, {i, c.shares});
    ASSERT_FALSE(share.empty());
    firstGroups.insert(groupIndex(plan, share.front()));
    // A share visits each of its groups in one stretch (one simulation or one read of it).
    std::set<std::size_t> finished;
    for (std::size_t k = 0; k < share.size(); ++k) {
      const std::size_t g = groupIndex(plan, share[k]);
      EXPECT_EQ(finished.count(g), 0u) << "share " << i << " returns to group " << g;
      if (k + 1 == share.size() || groupIndex(plan, share[k + 1]) != g) finished.insert(g);
    }
  }
  // As many different first groups as there can be: every share its own where groups are many.
  EXPECT_EQ(firstGroups.size(), std::min<std::size_t>(groups, static_cast<std::size_t>(c.shares)));
}

TEST_P(ShareSplit, EveryStrategyAndResolutionSpreadEvenlyOverTheShares) {
  // Cells of one (strategy, resolution, object count) cost about the same; a share with more of
  // the dear ones would finish last while the others wait. Each share gets as many as the groups
  // allow: the counts differ by at most one.
  const auto& c = GetParam();
  for (const bool oneResolution : {false, true}) {
    auto config = sweep(c.repeats, c.counts);
    if (oneResolution) config.sweep.resolutions = {800};  // env3: the strategies alone alternate
    const auto plan = cdb::planCells(config);
    std::map<std::string, std::vector<int>> perShare;  // strategy@resolution -> cells per share
    for (int i = 1; i <= c.shares; ++i)
      for (const auto& cell : cdb::shareOf(plan, {i, c.shares})) {
        auto& counts = perShare[cell.strategy + "@" + std::to_string(cell.resolution) + "/" +
                                std::to_string(cell.objectCount)];
        counts.resize(static_cast<std::size_t>(c.shares));
        ++counts[static_cast<std::size_t>(i - 1)];
      }
    for (const auto& [what, counts] : perShare) {
      const auto [lo, hi] = std::minmax_element(counts.begin(), counts.end());
      EXPECT_LE(*hi - *lo, 1) << what << (oneResolution ? " (one resolution)" : "");
    }
  }
}

TEST(RunPlan, OneSimulationOnTwoSharesSplitsEachStrategysResolutionsEvenly) {
  // One group (the quick profile's env1 and env2): the deal alone balances it. A cell's cost
  // grows with its resolution, so each share gets the same sum of resolutions of every strategy
  // (500+800+900+1200 against 600+700+1000+1100), not the odd ones against the even ones.
  const auto plan = cdb::planCells(sweep(1, {}));
  std::map<std::string, std::vector<int>> pixels;  // strategy -> sum of resolutions per share
  for (int i = 1; i <= 2; ++i)
    for (const auto& cell : cdb::shareOf(plan, {i, 2})) {
      auto& sums = pixels[cell.strategy];
      sums.resize(2);
      sums[static_cast<std::size_t>(i - 1)] += cell.resolution;
    }
  ASSERT_EQ(pixels.size(), 4u);
  for (const auto& [strategy, sums] : pixels) EXPECT_EQ(sums[0], sums[1]) << strategy;
}

TEST(RunPlan, StrategyRepeatsLimitAStrategyToTheFirstSimulations) {
  auto config = sweep(10, {});
  config.sweep.strategyRepeats = {{"quick_cullide", 3}};
  const auto plan = cdb::planCells(config);
  std::map<std::string, std::set<int>> repeatsOf;
  for (const auto& cell : plan) repeatsOf[cell.strategy].insert(cell.repeat);
  EXPECT_EQ(repeatsOf["quick_cullide"], (std::set<int>{0, 1, 2}));
  EXPECT_EQ(repeatsOf["cullide"].size(), 10u);
  EXPECT_EQ(repeatsOf["ours"].size(), 10u);
  EXPECT_EQ(plan.size(), (3u * 10u + 3u) * 8u);  // 3 strategies x 10 repeats + 3, 8 resolutions
  // Shares still take every cell once.
  std::set<std::string> seen;
  for (int i = 1; i <= 2; ++i)
    for (const auto& cell : cdb::shareOf(plan, {i, 2})) EXPECT_TRUE(seen.insert(cell.key()).second);
  EXPECT_EQ(seen.size(), plan.size());
}

// What draws nothing (the all_pairs reference, the CPU peers) is measured once per simulation,
// not once per resolution, as `cdbench check` does.
TEST(RunPlan, DetectorsThatDrawNothingGetOneCellPerSimulation) {
  auto config = sweep(2, {50, 100});
  config.sweep.strategies = {"cullide", "all_pairs", "fcl", "bullet", "ode"};
  const auto plan = cdb::planCells(config);
  std::map<std::string, std::size_t> cells;
  for (const auto& cell : plan) {
    ++cells[cell.strategy];
    if (cell.strategy != "cullide") {
      EXPECT_EQ(cell.resolution, cdb::kNoResolution) << cell.key();
    }
  }
  EXPECT_EQ(cells["cullide"], 2u * 2u * 8u);
  for (const char* s : {"all_pairs", "fcl", "bullet", "ode"}) EXPECT_EQ(cells[s], 2u * 2u) << s;
  // Keys stay unique.
  std::set<std::string> keys;
  for (const auto& cell : plan) EXPECT_TRUE(keys.insert(cell.key()).second) << cell.key();
}

TEST_P(ShareSplit, ASharesTakeOverOrderHoldsEveryOtherCellOnceFromEachShareEnd) {
  // (cdbench run --balance) A share that has finished its own cells takes the others' from their
  // ends, where their own shares get last, one share after the other in turn.
  const auto& c = GetParam();
  const auto plan = cdb::planCells(sweep(c.repeats, c.counts));
  for (int i = 1; i <= c.shares; ++i) {
    const auto order = cdb::takeOverOrder(plan, {i, c.shares});
    std::multiset<std::string> taken;
    for (const auto& cell : order) taken.insert(cell.key());
    std::multiset<std::string> others;
    for (const auto& cell : plan) others.insert(cell.key());
    for (const auto& cell : cdb::shareOf(plan, {i, c.shares})) others.erase(cell.key());
    EXPECT_EQ(taken, others) << "share " << i;
    // The first cells taken: the last of each other share, the next share first.
    std::size_t k = 0;
    for (int step = 1; step < c.shares; ++step) {
      const auto share = cdb::shareOf(plan, {(i - 1 + step) % c.shares + 1, c.shares});
      if (share.empty()) continue;
      ASSERT_LT(k, order.size());
      EXPECT_EQ(order[k++].key(), share.back().key()) << "share " << i << ", step " << step;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Sweeps, ShareSplit,
                         ::testing::Values(SplitCase{"env1_on_16", 10, {}, 16},
                                           SplitCase{"env1_on_2", 10, {}, 2},
                                           SplitCase{"two_counts_on_16", 10, {50, 100}, 16},
                                           SplitCase{"one_simulation_on_3", 1, {}, 3},
                                           SplitCase{"shard_test_sweep_on_3", 2, {12, 16}, 3}),
                         [](const auto& testCase) { return testCase.param.name; });

}  // namespace
