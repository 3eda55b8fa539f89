// frames.csv: the writer and reader follow kFrameColumns, keep the header and number formatting of
// the files already under results/, and `cdbench frame-columns` prints the same list.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "core/Errors.h"
#include "harness/tables/FrameCsv.h"
#include "tests/common/FreshTempDir.h"
#include "tests/common/ShellCommand.h"

namespace cdb {
namespace {

std::string readText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Column i holds 100 + i (and text columns "text<i>"), so a column read into another's member
// shows as a wrong value.
FrameRecord distinctRecord() {
  FrameRecord r;
  for (std::size_t i = 0; i < kFrameColumns.size(); ++i)
    std::visit(
        [&](auto member) {
          auto& value = r.*member;
          using T = std::remove_reference_t<decltype(value)>;
          if constexpr (std::is_same_v<T, std::string>)
            value = "text" + std::to_string(i);
          else if constexpr (std::is_same_v<T, double>)
            value = 100.25 + static_cast<double>(i);
          else
            value = static_cast<T>(100 + i);
        },
        kFrameColumns[i].field);
  return r;
}

TEST(FrameColumns, NamesAreUniqueAndNoTwoColumnsShareAMember) {
  std::set<std::string_view> names;
  for (const auto& c : kFrameColumns) {
    EXPECT_TRUE(names.insert(c.name).second) << c.name;
    EXPECT_FALSE(c.description.empty()) << c.name;
  }
  // Two columns on one member would both print the value the second wrote.
  const FrameRecord r = distinctRecord();
  std::set<std::string> values;
  for (const auto& c : kFrameColumns)
    std::visit(
        [&](auto member) {
          std::ostringstream text;
          text << r.*member;
          values.insert(text.str());
        },
        c.field);
  EXPECT_EQ(values.size(), kFrameColumns.size());
}

// The header of the files under results/ (those written before the tile counters lack the last
// five columns).
constexpr const char* kHeader =
    "environment,strategy,visibility,resolution,objects,repeat,frame,cd_ms,cull_ms,exact_ms,"
    "pcs_size,sets,pcs_triangles,pairs_tested,triangle_tests,colliding_pairs,truth_pairs,"
    "false_negatives,false_positives,culling_misses,queries,draws,triangles_drawn,"
    "pixels_tested,pixels_written,tile_tests,tile_tests_by_bounds,tile_tests_skipped,tile_writes,"
    "tile_writes_drawn,fetch_wait_ms,gpu_ms,gpu_setup_ms,gpu_bin_ms,gpu_sort_ms,gpu_evaluate_ms\n";

TEST(FrameCsv, HeaderIsTheOneOfTheResultsAlreadyWritten) {
  std::ostringstream out;
  writeFrameCsvHeader(out);
  EXPECT_EQ(out.str(), kHeader);
}

TEST(FrameCsv, ReadsEachColumnIntoItsMember) {
  const auto file = test::freshTempDir("frame_csv_members") / "frames.csv";
  {
    std::ofstream out(file);
    out << kHeader
        << "env9,cis,cpu,1,2,3,4,5.5,6.5,7.5,8,9,10,11,12,13,14,15,16,17,18,19,20,21,22,23,24,25,"
           "26,27,28.5,29.5,30.5,31.5,32.5,33.5\n";
  }
  const auto rows = readFrameCsv(file);
  ASSERT_EQ(rows.size(), 1u);
  // Set by member name, so a column read into another member shows.
  const FrameRecord expected{.environment = "env9",
                             .strategy = "cis",
                             .visibility = "cpu",
                             .resolution = 1,
                             .objects = 2,
                             .repeat = 3,
                             .frame = 4,
                             .cdMs = 5.5,
                             .cullMs = 6.5,
                             .exactMs = 7.5,
                             .pcsSize = 8,
                             .sets = 9,
                             .pcsTriangles = 10,
                             .pairsTested = 11,
                             .triangleTests = 12,
                             .collidingPairs = 13,
                             .truthPairs = 14,
                             .falseNegatives = 15,
                             .falsePositives = 16,
                             .cullingMisses = 17,
                             .queries = 18,
                             .draws = 19,
                             .trianglesDrawn = 20,
                             .pixelsTested = 21,
                             .pixelsWritten = 22,
                             .tileTests = 23,
                             .tileTestsByBounds = 24,
                             .tileTestsSkipped = 25,
                             .tileWrites = 26,
                             .tileWritesDrawn = 27,
                             .fetchWaitMs = 28.5,
                             .gpuMs = 29.5,
                             .gpuSetupMs = 30.5,
                             .gpuBinMs = 31.5,
                             .gpuSortMs = 32.5,
                             .gpuEvaluateMs = 33.5};
  for (const auto& c : kFrameColumns)
    std::visit([&](auto member) { EXPECT_EQ(rows[0].*member, expected.*member) << c.name; },
               c.field);
}

TEST(FrameCsv, RoundTripsEveryColumn) {
  const FrameRecord r = distinctRecord();
  const auto file = test::freshTempDir("frame_csv") / "frames.csv";
  {
    std::ofstream out(file);
    writeFrameCsvHeader(out);
    writeFrameCsvRow(out, r);
  }
  const auto rows = readFrameCsv(file);
  ASSERT_EQ(rows.size(), 1u);
  for (const auto& c : kFrameColumns)
    std::visit([&](auto member) { EXPECT_EQ(rows[0].*member, r.*member) << c.name; }, c.field);
}

TEST(FrameCsv, CommittedResultsReadAndWriteBackByteForByte) {
  const auto results = std::filesystem::path(CDBENCH_SOURCE_DIR) / "results" / "quick" / "cpu";
  for (const char* environment : {"env1", "env2", "env3"}) {
    const auto file = results / environment / "frames.csv";
    const auto rows = readFrameCsv(file);
    ASSERT_FALSE(rows.empty()) << file;
    std::ostringstream out;
    writeFrameCsvHeader(out);
    for (const auto& r : rows) writeFrameCsvRow(out, r);
    EXPECT_EQ(out.str(), readText(file)) << file;
  }
}

TEST(FrameCsv, AMalformedRowNamesFileAndLine) {
  const auto file = test::freshTempDir("frame_csv_bad") / "frames.csv";
  {
    std::ofstream out(file);
    writeFrameCsvHeader(out);
    writeFrameCsvRow(out, distinctRecord());
    out << "env1,cullide,cpu,fast\n";
  }
  try {
    (void)readFrameCsv(file);
    FAIL() << "read a row of 4 columns";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              file.string() + ":3: expected " + std::to_string(kFrameColumns.size()) +
                  " columns, got 4");
  }
}

TEST(FrameColumns, CdbenchPrintsThemWithTheirKinds) {
  const auto r = test::runShellCommand(std::string(CDBENCH_BINARY_DIR) + "/cdbench frame-columns");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::ostringstream expected;
  writeFrameColumnsCsv(expected);
  EXPECT_EQ(r.output, expected.str());
  EXPECT_NE(r.output.find("\nresolution,int,"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\ncd_ms,double,"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\nstrategy,string,"), std::string::npos) << r.output;
  EXPECT_NE(
      r.output.find("\nobjects,int,\"moving bodies (the thesis' \"\"number of objects\"\")\"\n"),
      std::string::npos)
      << r.output;
}

}  // namespace
}  // namespace cdb
