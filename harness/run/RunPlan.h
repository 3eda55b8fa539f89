#pragma once
// The cells of a run: every (object count, repeat, strategy, resolution) is measured on its own,
// so a run can stop and resume, or be split into shards and merged.
#include <cstdint>
#include <string>
#include <vector>

#include "scenes/ScenarioConfig.h"

namespace cdb {

struct Cell {
  int objectCount = -1;  // count of sweep.countedGroup; -1 = the config's own counts
  int repeat = 0;
  std::string strategy;
  int resolution = 0;  // 0 for a detector that draws nothing (kNoResolution)

  // File-name-safe and unique within a run: o50_r0_cullide_800 (o- when the config's counts).
  [[nodiscard]] std::string key() const;
  // Cells sharing a simulation (same object count and repeat).
  [[nodiscard]] bool sameFrames(const Cell& other) const {
    return objectCount == other.objectCount && repeat == other.repeat;
  }
};

// A share of the cells: the i-th of n (1-based), cells dealt in plan order back and forth over
// the shares, the deal turned by one share at each simulation group; see shareOf.
struct Shard {
  int index = 1;
  int count = 1;
  [[nodiscard]] bool whole() const { return count == 1; }
};

// Parses "i/n" (1 <= i <= n). Throws InputError.
[[nodiscard]] Shard parseShard(const std::string& text);

// The resolution of a cell whose detector draws nothing (the all_pairs reference, the CPU peers):
// its answer and time do not depend on a frame buffer, so it is measured once per simulation, not
// once per resolution, as `cdbench check` does; tables show it in every resolution's column.
inline constexpr int kNoResolution = 0;

// Every cell of the config's sweep, grouped by (object count, repeat) so that each group's frames
// are simulated once, then strategies, then resolutions (one cell at kNoResolution for a detector
// that draws nothing). A strategy in sweep.strategyRepeats has cells in the first N repeats only.
[[nodiscard]] std::vector<Cell> planCells(const ScenarioConfig& config);
// The share's cells (cell k of simulation group g, counted from the group's first, with p its
// place in its run of n: k mod n in even runs, n - 1 - k mod n in odd ones, when
// (p + g) mod n = i - 1), run starting at the simulation group ((i - 1) * groups / n) and
// wrapping around, so that shares started together simulate different groups first and later
// read each other's recordings instead of simulating every group each.
[[nodiscard]] std::vector<Cell> shareOf(const std::vector<Cell>& cells, const Shard& shard);
// The cells of the other shares, in the order a share that has finished its own takes them over
// (`cdbench run --balance`): each other share's cells from the last it would run backwards, so
// that the two meet at the end of its share, the shares after this one taken in turn (one cell
// of each, then the next of each).
[[nodiscard]] std::vector<Cell> takeOverOrder(const std::vector<Cell>& cells, const Shard& shard);

}  // namespace cdb
