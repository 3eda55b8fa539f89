#pragma once
// The correctness part of `cdbench check`: on each fixed frame of the plan, every strategy's
// colliding pairs against the ground truth's (SPEC: no pair pruned or split, pairs equal).
#include <cstddef>
#include <string>
#include <vector>

#include "culling/DetectorRegistry.h"
#include "culling/visibility/BackendResources.h"
#include "harness/check/CheckPlan.h"
#include "harness/check/CheckScenes.h"
#include "harness/measure/TruthComparison.h"

namespace cdb {

struct CorrectnessRow {
  std::string backend;  // the visibility backend ("-" for a CPU peer, which uses none)
  std::string scene;    // CheckScene::label()
  int frame = 0;
  std::string strategy;
  int resolution = 0;  // 0: a CPU peer, which decides the pairs itself and draws nothing
  std::size_t truthPairs = 0;
  std::size_t foundPairs = 0;
  TruthComparison comparison;  // for a CPU peer, cullingMisses counts its false negatives

  // Truth pairs exist (the frame tests something), none is missed, none is added, and none was
  // pruned or split across sets before the exact phase.
  [[nodiscard]] bool passed() const {
    return truthPairs > 0 && comparison.falseNegatives == 0 && comparison.falsePositives == 0 &&
           comparison.cullingMisses == 0;
  }
};

// Every case of `plan` for each of `strategies` (created by `registry`) on the visibility backend
// `backend`. What draws nothing (the CPU peers, the all_pairs reference: registry.usesBackend)
// runs at the first resolution only, and only when `withPeers`: neither the frame-buffer size nor
// the backend enters its answer.
[[nodiscard]] std::vector<CorrectnessRow> checkCorrectness(BackendResources& resources,
                                                           const std::string& backend, bool withPeers,
                                                           CheckScenes& scenes,
                                                           const std::vector<CorrectnessCase>& cases,
                                                           const std::vector<std::string>& strategies,
                                                           const DetectorRegistry& registry);

}  // namespace cdb
