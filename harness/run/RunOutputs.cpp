#include "harness/run/RunOutputs.h"

#include <sstream>

#include "harness/common/AtomicFile.h"
#include "harness/tables/FrameCsv.h"
#include "harness/tables/RunTables.h"

namespace cdb {

nlohmann::json frameTotals(const std::vector<FrameRecord>& rows) {
  std::uint64_t truthPairs = 0, falseNegatives = 0, falsePositives = 0;
  for (const auto& r : rows) {
    truthPairs += r.truthPairs;
    falseNegatives += r.falseNegatives;
    falsePositives += r.falsePositives;
  }
  return {{"frame_rows", rows.size()},
          {"truth_pairs", truthPairs},
          {"false_negatives", falseNegatives},
          {"false_positives", falsePositives}};
}

std::vector<Table> writeRunOutputs(const std::filesystem::path& dir,
                                   const std::vector<FrameRecord>& rows, const nlohmann::json& meta) {
  std::ostringstream csv;
  writeFrameCsvHeader(csv);
  for (const auto& r : rows) writeFrameCsvRow(csv, r);
  writeFileAtomically(dir / "frames.csv", csv.str());

  std::vector<Table> tables = runSummaryTables(rows, meta);
  std::ostringstream md, summaryCsv;
  MarkdownTableWriter().write(md, tables);
  CsvTableWriter("statistic").write(summaryCsv, tables);
  writeFileAtomically(dir / "summary.md", md.str());
  writeFileAtomically(dir / "summary.csv", summaryCsv.str());

  writeFileAtomically(dir / "meta.json", meta.dump(2) + "\n");
  return tables;
}

}  // namespace cdb
