#pragma once
// The tables a finished run prints and writes beside frames.csv (summary.md, summary.csv): the
// average and the maximum CD time per frame, rows = detectors in the run's order, columns =
// resolutions or object counts (both where both vary), each row's false negatives, and the
// environment and visibility backend in the titles. The report (scripts/report.py) computes the
// same averages from frames.csv, with intervals and the thesis' numbers beside them.
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/tables/FrameRecord.h"
#include "harness/tables/TableWriters.h"

namespace cdb {

// `meta`: the run's meta.json (its visibility backend and renderer, and whether the ground truth
// ran: config.ground_truth). An average is the mean over repeats of each repeat's mean over its
// frames; a maximum is the largest frame. A detector that draws nothing (its rows at resolution
// kNoResolution) shows its numbers in every resolution's column.
[[nodiscard]] std::vector<Table> runSummaryTables(const std::vector<FrameRecord>& rows,
                                                  const nlohmann::json& meta);

}  // namespace cdb
