#include "harness/RunOutputs.h"

#include <sstream>

#include "harness/AtomicFile.h"
#include "harness/CdTimeTables.h"
#include "harness/FrameCsv.h"

namespace cdb {

nlohmann::json frameTotals(const std::vector<FrameRecord>& rows) {
  std::uint64_t truthPairs = 0, falseNegatives = 0, falsePositives = 0;
  for (const auto& r : rows) {
    truthPairs += r.truthPairs;
    falseNegatives += r.falseNegatives;
    falsePositives += r.falsePositives;
  }
  return {{"frame_rows", rows.size()}, {"truth_pairs", truthPairs},
          {"false_negatives", falseNegatives}, {"false_positives", falsePositives}};
}

void writeRunOutputs(const std::filesystem::path& dir, const std::vector<FrameRecord>& rows,
                     const nlohmann::json& meta) {
  std::ostringstream csv;
  writeFrameCsvHeader(csv);
  for (const auto& r : rows) writeFrameCsvRow(csv, r);
  writeFileAtomically(dir / "frames.csv", csv.str());

  const auto cells = summariseCdTimes(rows);
  writeCdTimeTablesCsv(dir / "tables.csv", cells);
  std::string environment = rows.empty() ? std::string() : rows.front().environment;
  std::string renderer;
  if (meta.contains("visibility"))
    renderer = "visibility backend: " + meta["visibility"].value("backend", std::string("?")) + " (" +
               meta["visibility"].value("renderer", std::string()) + ")";
  if (meta.contains("gl") && meta["gl"].contains("renderer"))
    renderer += (renderer.empty() ? "" : "; ") + std::string("GL renderer: ") +
                meta["gl"]["renderer"].get<std::string>() + " (" +
                meta["gl"].value("version", std::string()) + ")";
  writeFileAtomically(dir / "tables.md", "# CD time tables: " + environment + "\n\n" + renderer +
                                             "\n\n" + cdTimeTablesMarkdown(cells));
  writeFileAtomically(dir / "meta.json", meta.dump(2) + "\n");
}

}  // namespace cdb
