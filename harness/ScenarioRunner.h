#pragma once
// `cdbench run`: simulate each (object count, repeat) once, replay its frames to every strategy
// at every resolution, time culling + exact phase per frame, check against the ground truth.
// Each finished cell is kept on disk (see CellStore); when every cell of the run is there,
// frames.csv and meta.json are written into the output folder.
#include "harness/RunOptions.h"
#include "harness/TableWriters.h"
#include "harness/WallTimeBreakdown.h"
#include "scenes/ScenarioConfig.h"

namespace cdb {

struct RunSummary {
  std::size_t cellsRun = 0;      // measured by this invocation
  std::size_t cellsSkipped = 0;  // already finished (resumed)
  // When cells were resumed: the other builds that measured the folder's kept cells (their times
  // are those builds').
  std::vector<std::string> resumedFromOtherBuilds;
  std::size_t frameRows = 0;     // rows of frames.csv, 0 while the run is incomplete
  bool complete = false;         // every cell of the whole run is on disk and frames.csv written
  std::uint64_t falseNegatives = 0;
  std::uint64_t falsePositives = 0;
  WallTimeBreakdown time;  // this invocation's wall time, by where it went
  std::vector<Table> tables;  // the whole run's average/maximum table (summary.md), once complete
};

// Thrown when SIGINT/SIGTERM stopped the run between frames; finished cells are kept.
struct RunInterrupted {
  int signal = 0;
  std::size_t cellsDone = 0;
};

// The config with the command line's overrides applied and checked (strategy names, ranges).
[[nodiscard]] ScenarioConfig effectiveConfig(const RunOptions& options);

RunSummary runScenario(const RunOptions& options);

}  // namespace cdb
