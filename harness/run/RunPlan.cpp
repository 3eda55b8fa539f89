#include "harness/run/RunPlan.h"

#include <algorithm>

#include "core/Errors.h"
#include "culling/DetectorRegistry.h"

namespace cdb {

std::string Cell::key() const {
  // Appended piece by piece: GCC 12 reports a false -Wrestrict on `"o" + std::string(...)`.
  std::string key = "o";
  key += objectCount < 0 ? std::string("-") : std::to_string(objectCount);
  key += "_r" + std::to_string(repeat) + "_" + strategy + "_" + std::to_string(resolution);
  return key;
}

Shard parseShard(const std::string& text) {
  const auto slash = text.find('/');
  Shard s;
  try {
    if (slash == std::string::npos) throw std::invalid_argument("no slash");
    std::size_t used = 0;
    s.index = std::stoi(text.substr(0, slash), &used);
    if (used != slash) throw std::invalid_argument("index");
    const std::string n = text.substr(slash + 1);
    s.count = std::stoi(n, &used);
    if (used != n.size()) throw std::invalid_argument("count");
  } catch (const std::exception&) {
    throw InputError("--shard '" + text + "': expected i/n, e.g. 1/4");
  }
  if (s.count < 1 || s.index < 1 || s.index > s.count)
    throw InputError("--shard '" + text + "': expected 1 <= i <= n");
  return s;
}

std::vector<Cell> planCells(const ScenarioConfig& config) {
  std::vector<int> counts = config.sweep.objectCounts;
  if (counts.empty()) counts.push_back(-1);
  std::vector<Cell> cells;
  for (int count : counts)
    for (int repeat = 0; repeat < config.sweep.repeats; ++repeat)
      for (const auto& strategy : config.sweep.strategies) {
        const auto limit = config.sweep.strategyRepeats.find(strategy);
        if (limit != config.sweep.strategyRepeats.end() && repeat >= limit->second) continue;
        if (!DetectorRegistry::builtin().usesBackend(strategy)) {
          cells.push_back({count, repeat, strategy, kNoResolution});
          continue;
        }
        for (int resolution : config.sweep.resolutions)
          cells.push_back({count, repeat, strategy, resolution});
      }
  return cells;
}

std::vector<Cell> shareOf(const std::vector<Cell>& cells, const Shard& shard) {
  // Dealt in plan order to shares 1..n, then n..1, then 1..n again (so that within a group, where
  // resolutions rise from cell to cell, no share always gets the larger of each n), the deal
  // turned by one share at each simulation group: cell k of group g (k counted from the group's
  // first cell, p its place in its run of n: k mod n, or n - 1 - k mod n in every second run)
  // goes to share (p + g) mod n. Without the turn, a cell's place in its group would fix its
  // share, and so would its strategy and resolution (with 2 shares and one resolution, one share
  // would get every cullide cell and the other every cullide_bvh cell); with it, every (strategy,
  // resolution) is spread over the shares as evenly as the groups allow.
  // Each dealt cell keeps the index of its simulation group.
  std::vector<Cell> dealt;
  std::vector<std::size_t> groupOf;
  const auto n = static_cast<std::size_t>(shard.count);
  std::size_t group = 0, groupStart = 0;
  for (std::size_t k = 0; k < cells.size(); ++k) {
    if (k > 0 && !cells[k].sameFrames(cells[k - 1])) ++group, groupStart = k;
    const std::size_t inGroup = k - groupStart;
    const std::size_t place = (inGroup / n) % 2 == 0 ? inGroup % n : n - 1 - inGroup % n;
    if (static_cast<int>((place + group) % n) == shard.index - 1) {
      dealt.push_back(cells[k]);
      groupOf.push_back(group);
    }
  }
  if (dealt.empty()) return dealt;
  // Shares run at once start at groups spread over the plan, so that they do not all simulate
  // the same group at the same time: the share that reaches a group first keeps its recording and
  // the others read it (CellStore::recordingPath).
  const std::size_t groups = group + 1;
  const std::size_t start = static_cast<std::size_t>(shard.index - 1) * groups / n;
  const auto first = std::find_if(groupOf.begin(), groupOf.end(),
                                  [&](std::size_t g) { return g >= start; });
  std::rotate(dealt.begin(), dealt.begin() + (first - groupOf.begin()), dealt.end());
  return dealt;
}

std::vector<Cell> takeOverOrder(const std::vector<Cell>& cells, const Shard& shard) {
  std::vector<std::vector<Cell>> others;
  for (int k = 1; k < shard.count; ++k)
    others.push_back(shareOf(cells, {(shard.index - 1 + k) % shard.count + 1, shard.count}));
  std::vector<Cell> order;
  for (std::size_t back = 1;; ++back) {
    bool any = false;
    for (const auto& share : others)
      if (back <= share.size()) order.push_back(share[share.size() - back]), any = true;
    if (!any) return order;
  }
}

}  // namespace cdb
