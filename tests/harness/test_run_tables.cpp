// The run's own average/maximum table: what it computes from the frames (runSummaryTables) and the
// three forms one table is written in (console, Markdown, CSV).
#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/run/RunPlan.h"
#include "harness/tables/RunTables.h"
#include "harness/tables/TableWriters.h"

namespace cdb {
namespace {

Table smallTable(std::string key, double cullide, double fcl) {
  Table t;
  t.title = "env3: " + key + " CD time per frame (ms)";
  t.key = std::move(key);
  t.header = {"strategy \\ resolution", "256", "false negatives"};
  t.rows = {{std::string("cullide"), cullide, std::uint64_t{0}},
            {std::string("fcl"), fcl, std::uint64_t{12}},
            {std::string("sorted"), std::monostate{}, std::string("n/a")}};
  return t;
}

std::string written(const TableWriter& writer, const std::vector<Table>& tables) {
  std::ostringstream out;
  writer.write(out, tables);
  return out.str();
}

TEST(TableWriters, ConsoleAlignsNumbersRightTextLeftBetweenRules) {
  Table t = smallTable("average", 8.711, 0.0558);
  t.notes = {"a note"};
  EXPECT_EQ(written(ConsoleTableWriter(), {t}),
            "env3: average CD time per frame (ms)\n"
            "----------------------------------------------\n"
            "strategy \\ resolution    256   false negatives\n"
            "----------------------------------------------\n"
            "cullide                 8.71                 0\n"
            "fcl                     0.06                12\n"
            "sorted                                     n/a\n"
            "a note\n");
}

TEST(TableWriters, ConsoleLinesUpTablesWithTheSameHeader) {
  const std::string text = written(ConsoleTableWriter(1), {smallTable("average", 8.7, 0.06),
                                                           smallTable("maximum", 1234.5, 0.2)});
  // 1234.5 widens the resolution column of both tables: every rule is as long.
  std::istringstream lines(text);
  std::string line;
  std::vector<std::size_t> rules;
  while (std::getline(lines, line))
    if (!line.empty() && line.find_first_not_of('-') == std::string::npos) rules.push_back(line.size());
  ASSERT_EQ(rules.size(), 4u) << text;
  for (std::size_t width : rules) EXPECT_EQ(width, rules.front()) << text;
  EXPECT_NE(text.find("cullide                    8.7"), std::string::npos) << text;
  EXPECT_NE(text.find("cullide                 1234.5"), std::string::npos) << text;
}

TEST(TableWriters, MarkdownRightAlignsNumberColumns) {
  Table t = smallTable("average", 8.711, 0.0558);
  t.notes = {"a note"};
  EXPECT_EQ(written(MarkdownTableWriter(), {t}),
            "## env3: average CD time per frame (ms)\n\n"
            "| strategy \\ resolution | 256 | false negatives |\n"
            "|---|---:|---:|\n"
            "| cullide | 8.71 | 0 |\n"
            "| fcl | 0.06 | 12 |\n"
            "| sorted |  | n/a |\n"
            "\na note\n");
}

TEST(TableWriters, CsvOneHeaderEachRowAfterItsTablesKey) {
  Table odd = smallTable("maximum", 1.0, 2.0);
  odd.rows[0][0] = std::string("a,b \"c\"");
  EXPECT_EQ(written(CsvTableWriter("statistic"), {smallTable("average", 8.711, 0.0558), odd}),
            "statistic,strategy \\ resolution,256,false negatives\n"
            "average,cullide,8.7110,0\n"
            "average,fcl,0.0558,12\n"
            "average,sorted,,n/a\n"
            "maximum,\"a,b \"\"c\"\"\",1.0000,0\n"
            "maximum,fcl,2.0000,12\n"
            "maximum,sorted,,n/a\n");
  Table other = smallTable("maximum", 1.0, 2.0);
  other.header[1] = "512";
  std::ostringstream out;
  EXPECT_THROW(CsvTableWriter("statistic").write(out, {smallTable("average", 1, 2), other}),
               std::invalid_argument);
}

FrameRecord frame(const std::string& strategy, int resolution, int objects, int repeat, int index,
                  double cdMs, std::uint64_t falseNegatives = 0) {
  FrameRecord r;
  r.environment = "env1";
  r.strategy = strategy;
  r.resolution = resolution;
  r.objects = objects;
  r.repeat = repeat;
  r.frame = index;
  r.cdMs = cdMs;
  r.falseNegatives = falseNegatives;
  return r;
}

const nlohmann::json kMeta = {{"visibility", {{"backend", "cpu"}, {"renderer", "test rasteriser"}}},
                              {"config", {{"ground_truth", true}}}};

// The cell at `column` (1-based after the strategy) of `strategy`'s row.
const TableCell& cellOf(const Table& t, const std::string& strategy, std::size_t column) {
  for (const auto& row : t.rows)
    if (std::get<std::string>(row.front()) == strategy) return row.at(column);
  throw std::out_of_range(strategy);
}

TEST(RunSummaryTables, AverageOfRepeatMeansMaximumOfFramesAndSharedReferenceColumns) {
  std::vector<FrameRecord> rows;
  // ours at 500 px: repeat 0 frames of 1 and 3 ms (mean 2), repeat 1 one frame of 10 ms: the
  // average is the mean of the repeats' means, 6, not the mean of the frames, 4.67.
  rows.push_back(frame("ours", 500, 50, 0, 0, 1.0));
  rows.push_back(frame("ours", 500, 50, 0, 10, 3.0, 2));
  rows.push_back(frame("ours", 500, 50, 1, 0, 10.0));
  rows.push_back(frame("ours", 600, 50, 0, 0, 4.0, 1));
  // all_pairs draws nothing: one cell at no resolution, shown at 500 and at 600.
  rows.push_back(frame("all_pairs", kNoResolution, 50, 0, 0, 7.0));
  rows.push_back(frame("all_pairs", kNoResolution, 50, 0, 10, 9.0));
  const auto tables = runSummaryTables(rows, kMeta);
  ASSERT_EQ(tables.size(), 2u);
  const Table& avg = tables[0];
  const Table& max = tables[1];
  EXPECT_EQ(avg.key, "average");
  EXPECT_EQ(max.key, "maximum");
  EXPECT_EQ(avg.header, (std::vector<std::string>{"strategy \\ resolution", "500", "600", "false negatives"}));
  EXPECT_NE(avg.title.find("env1"), std::string::npos) << avg.title;
  EXPECT_NE(avg.title.find("50 objects"), std::string::npos) << avg.title;
  EXPECT_NE(avg.title.find("cpu backend (test rasteriser)"), std::string::npos) << avg.title;

  EXPECT_DOUBLE_EQ(std::get<double>(cellOf(avg, "ours", 1)), 6.0);
  EXPECT_DOUBLE_EQ(std::get<double>(cellOf(avg, "ours", 2)), 4.0);
  EXPECT_DOUBLE_EQ(std::get<double>(cellOf(max, "ours", 1)), 10.0);
  EXPECT_EQ(std::get<std::uint64_t>(cellOf(avg, "ours", 3)), 3u);
  for (std::size_t column : {1u, 2u}) {
    EXPECT_DOUBLE_EQ(std::get<double>(cellOf(avg, "all_pairs", column)), 8.0);
    EXPECT_DOUBLE_EQ(std::get<double>(cellOf(max, "all_pairs", column)), 9.0);
  }
  bool said = false;
  for (const auto& note : max.notes) said = said || note.find("all_pairs draws nothing") == 0;
  EXPECT_TRUE(said);
}

TEST(RunSummaryTables, ColumnsFollowWhatTheRunSwept) {
  std::vector<FrameRecord> rows;
  for (int n : {50, 75}) {
    rows.push_back(frame("cullide", 800, n, 0, 0, n / 10.0));
    rows.push_back(frame("fcl", kNoResolution, n, 0, 0, n / 100.0));
  }
  auto tables = runSummaryTables(rows, kMeta);
  EXPECT_EQ(tables[0].header, (std::vector<std::string>{"strategy \\ objects", "50", "75", "false negatives"}));
  EXPECT_NE(tables[0].title.find("800x800 pixels"), std::string::npos) << tables[0].title;
  EXPECT_DOUBLE_EQ(std::get<double>(cellOf(tables[0], "fcl", 2)), 0.75);

  // Both swept: one column per (objects, resolution) measured.
  rows.push_back(frame("cullide", 64, 50, 0, 0, 1.0));
  tables = runSummaryTables(rows, kMeta);
  EXPECT_EQ(tables[0].header, (std::vector<std::string>{"strategy \\ objects@resolution", "50@64",
                                                        "50@800", "75@800", "false negatives"}));
  EXPECT_DOUBLE_EQ(std::get<double>(cellOf(tables[0], "cullide", 1)), 1.0);
  EXPECT_DOUBLE_EQ(std::get<double>(cellOf(tables[0], "cullide", 3)), 7.5);
  EXPECT_DOUBLE_EQ(std::get<double>(cellOf(tables[0], "fcl", 1)), 0.5);
  EXPECT_DOUBLE_EQ(std::get<double>(cellOf(tables[0], "fcl", 2)), 0.5);

  // Without the ground truth the false negatives are not a number.
  const nlohmann::json noTruth = {{"visibility", {{"backend", "gl-flags"}}},
                                  {"config", {{"ground_truth", false}}}};
  tables = runSummaryTables(rows, noTruth);
  EXPECT_EQ(std::get<std::string>(cellOf(tables[0], "cullide", 4)), "not checked");
  EXPECT_NE(tables[0].title.find("gl-flags backend"), std::string::npos) << tables[0].title;
}

}  // namespace
}  // namespace cdb
