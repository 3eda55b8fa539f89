#pragma once
// The result files of a complete run (or of merged shards): frames.csv and meta.json, each written
// atomically, meta.json last. Average and maximum CD time per cell are the report's
// (scripts/report.py), from frames.csv: one computation, with its intervals over repeats.
#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/FrameRecord.h"

namespace cdb {

// meta.json's summary of the frames: frame_rows, truth_pairs, false_negatives, false_positives.
[[nodiscard]] nlohmann::json frameTotals(const std::vector<FrameRecord>& rows);

void writeRunOutputs(const std::filesystem::path& dir, const std::vector<FrameRecord>& rows,
                     const nlohmann::json& meta);

}  // namespace cdb
