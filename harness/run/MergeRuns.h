#pragma once
// `cdbench merge --out OUT DIR...`: joins the cells of shards of one run (each DIR written by
// `cdbench run ... --shard i/n`, or the same DIR shared by all shards) into the same frames.csv
// and meta.json an unsharded run writes (with summary.md and summary.csv).
#include <filesystem>
#include <vector>

#include "harness/tables/TableWriters.h"

namespace cdb {

struct MergeSummary {
  std::size_t cells = 0;
  std::size_t frameRows = 0;
  std::vector<Table> tables;  // the run's average/maximum table, as summary.md holds it
};

// Throws InputError when a DIR is not a run folder, the DIRs come from different runs, or a cell
// of the run is missing from all of them.
MergeSummary mergeRuns(const std::filesystem::path& outDir,
                       const std::vector<std::filesystem::path>& runDirs);

}  // namespace cdb
