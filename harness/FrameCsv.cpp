#include "harness/FrameCsv.h"

#include <charconv>
#include <fstream>
#include <sstream>
#include <string>

#include "core/Errors.h"

namespace cdb {

namespace {
constexpr const char* kHeader =
    "environment,strategy,visibility,resolution,objects,repeat,frame,cd_ms,cull_ms,exact_ms,pcs_size,"
    "sets,pcs_triangles,pairs_tested,triangle_tests,colliding_pairs,truth_pairs,false_negatives,"
    "false_positives,culling_misses,queries,draws,triangles_drawn,pixels_tested,pixels_written";
constexpr int kColumns = 25;
}  // namespace

void writeFrameCsvHeader(std::ostream& out) { out << kHeader << '\n'; }

void writeFrameCsvRow(std::ostream& out, const FrameRecord& r) {
  out << r.environment << ',' << r.strategy << ',' << r.visibility << ',' << r.resolution << ',' << r.objects << ','
      << r.repeat << ',' << r.frame << ',' << r.cdMs << ',' << r.cullMs << ',' << r.exactMs << ','
      << r.pcsSize << ',' << r.sets << ',' << r.pcsTriangles << ',' << r.pairsTested << ','
      << r.triangleTests << ',' << r.collidingPairs << ',' << r.truthPairs << ','
      << r.falseNegatives << ',' << r.falsePositives << ',' << r.cullingMisses << ','
      << r.queries << ',' << r.draws << ',' << r.trianglesDrawn << ',' << r.pixelsTested << ','
      << r.pixelsWritten << '\n';
}

std::vector<FrameRecord> readFrameCsv(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string() + ": cannot open frames file");
  std::string line;
  if (!std::getline(in, line) || line != kHeader)
    throw InputError(file.string() + ":1: expected the frames.csv header");
  std::vector<FrameRecord> rows;
  int lineNo = 1;
  while (std::getline(in, line)) {
    ++lineNo;
    if (line.empty()) continue;
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) f.push_back(cell);
    if (static_cast<int>(f.size()) != kColumns)
      throw InputError(file.string() + ":" + std::to_string(lineNo) + ": expected " +
                       std::to_string(kColumns) + " columns, got " + std::to_string(f.size()));
    try {
      FrameRecord r;
      std::size_t i = 0;
      r.environment = f[i++];
      r.strategy = f[i++];
      r.visibility = f[i++];
      r.resolution = std::stoi(f[i++]);
      r.objects = std::stoi(f[i++]);
      r.repeat = std::stoi(f[i++]);
      r.frame = std::stoi(f[i++]);
      r.cdMs = std::stod(f[i++]);
      r.cullMs = std::stod(f[i++]);
      r.exactMs = std::stod(f[i++]);
      for (std::uint64_t* v : {&r.pcsSize, &r.sets, &r.pcsTriangles, &r.pairsTested,
                               &r.triangleTests, &r.collidingPairs, &r.truthPairs,
                               &r.falseNegatives, &r.falsePositives, &r.cullingMisses,
                               &r.queries, &r.draws, &r.trianglesDrawn, &r.pixelsTested,
                               &r.pixelsWritten})
        *v = std::stoull(f[i++]);
      rows.push_back(std::move(r));
    } catch (const std::logic_error&) {
      throw InputError(file.string() + ":" + std::to_string(lineNo) + ": expected numbers");
    }
  }
  return rows;
}

}  // namespace cdb
