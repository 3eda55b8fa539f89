#pragma once
// The result files of a complete run (or of merged shards): frames.csv, the run's own average and
// maximum table as summary.md and summary.csv (RunTables.h), and meta.json, each written
// atomically, meta.json last. The report (scripts/report.py) computes its tables from frames.csv,
// with intervals over repeats and the thesis' numbers beside them.
#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/tables/FrameRecord.h"
#include "harness/tables/TableWriters.h"

namespace cdb {

// meta.json's summary of the frames: frame_rows, truth_pairs, false_negatives, false_positives.
[[nodiscard]] nlohmann::json frameTotals(const std::vector<FrameRecord>& rows);

// Writes the files and returns the summary tables (what `cdbench run` prints).
std::vector<Table> writeRunOutputs(const std::filesystem::path& dir,
                                   const std::vector<FrameRecord>& rows, const nlohmann::json& meta);

}  // namespace cdb
