#pragma once
// The timing part of `cdbench check`: ratios of culling times measured in this one process on the
// same frames, never absolute times, so that a shared, noisy machine does not decide the result.
#include <string>
#include <vector>

#include "culling/StrategyRegistry.h"
#include "harness/CheckPlan.h"
#include "harness/CheckScenes.h"
#include "render/HeadlessGlContext.h"

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
  std::string key;  // SpeedupCase::key() or FloorCase::key(strategy): the baseline's key
  RatioKind kind = RatioKind::Speedup;
  double value = 0;
  double numeratorMs = 0, denominatorMs = 0;  // the two times of the median round
};

// Each speedup case: both strategies attached to one backend, one untimed cull each, then
// `repeats` rounds in which each culls the frame once, the order alternating from round to round
// so that neither always runs first after the other.
[[nodiscard]] std::vector<RatioMeasurement> measureSpeedups(HeadlessGlContext& gl, CheckScenes& scenes,
                                                            const std::vector<SpeedupCase>& cases,
                                                            const StrategyRegistry& registry);

// Each floor case for each of `strategies` that issues GL work: its work recorded from one cull
// (recordCullWork) and prepared for replay, one untimed cull and replay, then `rounds` rounds of
// one cull and one replay, the order alternating. A strategy that issues no GL work (a CPU peer)
// has no floor and no measurement: its name is added to `withoutFloor` (once) instead.
[[nodiscard]] std::vector<RatioMeasurement> measureFloors(HeadlessGlContext& gl, CheckScenes& scenes,
                                                          const std::vector<FloorCase>& cases,
                                                          const std::vector<std::string>& strategies,
                                                          const StrategyRegistry& registry,
                                                          std::vector<std::string>& withoutFloor);

}  // namespace cdb
