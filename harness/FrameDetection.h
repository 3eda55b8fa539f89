#pragma once
// One frame of collision detection as the harness times it: the strategy culls the poses, then
// the exact phase tests what the culling left (or, for a strategy that decides the pairs itself,
// its pairs are the answer). The runner, the check, the benchmarks and the strategy-vs-truth test
// all call this, so that what is timed and what is compared with the truth is the same everywhere.
#include <span>

#include "core/Pose.h"
#include "culling/CullingStrategy.h"
#include "culling/exact/ExactPhase.h"

namespace cdb {

struct DetectedFrame {
  CullingResult culled;     // `decided` moved into `report` for strategies that decide themselves
  CollisionReport report;   // the colliding pairs (sorted, unique) and the exact phase's counters
  double cullMs = 0.0;      // the strategy's cull(), backend waits included
  double exactMs = 0.0;     // the exact phase (0 for a strategy that decides itself)
  [[nodiscard]] double cdMs() const { return cullMs + exactMs; }
  [[nodiscard]] bool decidedByStrategy() const { return culled.decided.has_value(); }
};

// `exact` must be built for the scene the strategy is attached to.
[[nodiscard]] DetectedFrame detectFrame(CullingStrategy& strategy, ExactPhase& exact,
                                        std::span<const Pose> poses, int frame);

}  // namespace cdb
