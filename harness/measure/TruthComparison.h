#pragma once
// harness/measure/: what measuring a strategy on frames takes, shared by `cdbench run`
// (harness/run/), `cdbench check` (harness/check/) and the benchmarks (bench/). BackendWarmUp and
// DetectorWarmUp take first-use costs out of the first timed frame; TruthComparison (this file)
// counts a strategy's misses against the ground truth and FloorComparison sets its culling time
// against its backend's floor; RecordedScene simulates a config once and keeps its frames.
//
// A strategy's answer on one frame against the ground truth's.
#include <cstdint>
#include <vector>

#include "culling/CollisionDetector.h"
#include "culling/PotentiallyCollidingSets.h"
#include "culling/exact/ObjectPair.h"

namespace cdb {

struct TruthComparison {
  std::uint64_t falseNegatives = 0;  // truth pairs missing from the final colliding pairs
  std::uint64_t falsePositives = 0;  // final pairs the truth does not have
  std::uint64_t cullingMisses = 0;   // truth pairs not together in any one set (pruned or split),
                                     // or left out of the pairs a set lists
};

// Both pair lists sorted and unique.
[[nodiscard]] TruthComparison compareWithTruth(const std::vector<ObjectPair>& truth,
                                               const std::vector<ObjectPair>& found,
                                               const PotentiallyCollidingSets& sets,
                                               std::size_t objectCount);

// The same for a detector's answer on one frame. A detector that culls nothing (a CPU peer) leaves
// no sets, so every pair it misses is a culling miss too.
[[nodiscard]] TruthComparison compareWithTruth(const std::vector<ObjectPair>& truth,
                                               const DetectedFrame& detected,
                                               std::size_t objectCount);

}  // namespace cdb
