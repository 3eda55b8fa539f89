#pragma once
// harness/run/, the room of `cdbench run` and `cdbench merge`. RunOptions is what a run was asked
// for and RunPlan its cells and shards; CellFrames simulates (or reads back) the frames and the
// ground truth the cells are measured on, CellMeasurement times one cell's frames, and CellStore
// keeps each finished cell on disk so a run resumes; RunMeta (with CullingSpecJson) and
// RunOutputs write meta.json, frames.csv and the summaries once every cell is there, and
// MergeRuns does the same from the cells of shards; WallTimeBreakdown, ProgressBar and
// InterruptFlag account for, show and stop a run. ScenarioRunner (this file) drives them. What
// frames.csv and the tables look like is in harness/tables/, the warm-ups and the comparison with
// the ground truth in harness/measure/.
//
// `cdbench run`: simulate each (object count, repeat) once, replay its frames to every strategy
// at every resolution, time culling + exact phase per frame, check against the ground truth.
// Each finished cell is kept on disk (see CellStore); when every cell of the run is there,
// frames.csv and meta.json are written into the output folder.
#include "harness/run/RunOptions.h"
#include "harness/run/WallTimeBreakdown.h"
#include "harness/tables/TableWriters.h"
#include "scenes/ScenarioConfig.h"

namespace cdb {

struct RunSummary {
  std::size_t cellsRun = 0;      // measured by this invocation
  std::size_t cellsSkipped = 0;  // already finished (resumed)
  std::size_t cellsTakenOver = 0;  // of cellsRun, other shares' (--balance)
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
