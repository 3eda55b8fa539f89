#pragma once
// What every CPU peer hands back: the pairs its library reported, in the library's order and
// possibly repeated, turned into the harness' answer (sorted, unique). The peers run no triangle
// tests of the project, so only pairsTested (pairs the library's narrow phase examined) is counted.
#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "culling/CullingStrategy.h"
#include "culling/exact/ObjectPair.h"

namespace cdb {

[[nodiscard]] inline CullingResult peerResult(std::vector<ObjectPair> pairs,
                                              std::uint64_t pairsTested) {
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  CollisionReport report;
  report.collidingPairs = std::move(pairs);
  report.pairsTested = pairsTested;
  CullingResult result;
  result.decided = std::move(report);
  return result;
}

}  // namespace cdb
