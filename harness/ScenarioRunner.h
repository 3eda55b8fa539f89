#pragma once
// `cdbench run`: simulate each (object count, repeat) once, replay its frames to every strategy
// at every resolution, time culling + exact phase per frame, check against the ground truth, and
// write frames.csv, tables.csv, tables.md and meta.json into the output folder.
#include "harness/RunOptions.h"
#include "scenes/ScenarioConfig.h"

namespace cdb {

struct RunSummary {
  std::size_t frameRows = 0;
  std::uint64_t falseNegatives = 0;
  std::uint64_t falsePositives = 0;
};

// The config with the command line's overrides applied and checked (strategy names, ranges).
[[nodiscard]] ScenarioConfig effectiveConfig(const RunOptions& options);

RunSummary runScenario(const RunOptions& options);

}  // namespace cdb
