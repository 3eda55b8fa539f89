#pragma once
// The timing part of `cdbench check`: ratios of culling times measured in this one process on the
// same frames, never absolute times, so that a shared, noisy machine does not decide the result.
#include <string>
#include <vector>

#include "culling/DetectorRegistry.h"
#include "culling/visibility/BackendResources.h"
#include "harness/check/CheckPlan.h"
#include "harness/check/CheckScenes.h"

namespace cdb {

enum class RatioKind {
  Speedup,    // a baseline strategy's time over another's: higher is better
  OverFloor,  // a strategy's time over its backend floor: lower is better
};

// A ratio is measured in rounds, each timing both sides moments apart, under the same load; the
// value is the median of the rounds' ratios. On a shared machine the CPU time llvmpipe gets
// changes from second to second, and a ratio of two times taken seconds apart (or of each side's
// best over all rounds) follows those changes; the median drops a round hit on one side only.
struct RatioMeasurement {
  // "<backend>: " + SpeedupCase::key() or FloorCase::key(strategy): the baseline's key
  std::string key;
  std::string backend;  // the visibility backend both sides ran on
  RatioKind kind = RatioKind::Speedup;
  double value = 0;
  double numeratorMs = 0, denominatorMs = 0;  // the two times of the median round
};

// Each speedup case on the visibility backend `backend`: both strategies attached to one backend, one untimed cull each, then
// `repeats` rounds in which each culls the frame once, the order alternating from round to round
// so that neither always runs first after the other.
[[nodiscard]] std::vector<RatioMeasurement> measureSpeedups(BackendResources& resources,
                                                            const std::string& backend,
                                                            CheckScenes& scenes,
                                                            const std::vector<SpeedupCase>& cases,
                                                            const DetectorRegistry& registry);

// Each floor case for each of `strategies` that issues backend work, on `backend`: its work
// recorded from one cull and prepared for replay on the backend's floor (FloorSetup), one untimed
// cull and replay, then `rounds` rounds of one cull and one replay, the order alternating. A
// strategy that issues no backend work (a CPU peer) has no floor and no measurement: its name is
// added to `withoutFloor` (once) instead.
[[nodiscard]] std::vector<RatioMeasurement> measureFloors(BackendResources& resources,
                                                          const std::string& backend,
                                                          CheckScenes& scenes,
                                                          const std::vector<FloorCase>& cases,
                                                          const std::vector<std::string>& strategies,
                                                          const DetectorRegistry& registry,
                                                          std::vector<std::string>& withoutFloor);

}  // namespace cdb
