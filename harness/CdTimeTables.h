#pragma once
// The thesis' tables (4.1-4.3): average and maximum CD time per strategy and per resolution or
// object count, over every frame of every repeat of a cell.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "harness/FrameRecord.h"

namespace cdb {

struct CdTimeCell {
  std::string environment;
  std::string strategy;
  int resolution = 0;
  int objects = 0;
  double averageMs = 0;
  double maximumMs = 0;
  std::uint64_t frames = 0;
  std::uint64_t falseNegatives = 0;
};

// Cells in order of first appearance of (environment, strategy), then resolution, then objects.
[[nodiscard]] std::vector<CdTimeCell> summariseCdTimes(const std::vector<FrameRecord>& frames);

// Long form, one row per statistic and cell (the shape of the thesis' tables.csv):
// table,environment,statistic,strategy,resolution,objects,cd_time_ms,frames,false_negatives
void writeCdTimeTablesCsv(const std::filesystem::path& file, const std::vector<CdTimeCell>& cells);
// Markdown: per environment an average and a maximum table, rows = strategies, columns =
// resolutions, or object counts when those are what varies.
[[nodiscard]] std::string cdTimeTablesMarkdown(const std::vector<CdTimeCell>& cells);

}  // namespace cdb
