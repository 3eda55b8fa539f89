// The cdbench binary end to end: a small env3 run writes frames.csv and meta.json with no false
// negative; bad input exits 2 with one line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "harness/FrameCsv.h"
#include "tests/common/FreshTempDir.h"
#include "tests/common/ShellCommand.h"

namespace {

cdb::test::CommandResult runCdbench(const std::string& args) {
  return cdb::test::runShellCommand(std::string(CDBENCH_BINARY_DIR) + "/cdbench " + args + " 2>&1");
}

std::filesystem::path tempDir(const std::string& name) { return cdb::test::freshTempDir("cli_" + name); }

const std::string kConfigs = std::string(CDBENCH_SOURCE_DIR) + "/configs/";

TEST(Cli, Env3RunWritesFramesAndMetaWithNoFalseNegatives) {
  const auto out = tempDir("env3");
  const auto r = runCdbench("run " + kConfigs + "env3.yaml --strategies cullide --objects 20 "
                            "--frames 4 --repeats 1 --resolutions 128 --quiet --out " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* f : {"frames.csv", "meta.json"})
    EXPECT_TRUE(std::filesystem::exists(out / f)) << f;
  const auto rows = cdb::readFrameCsv(out / "frames.csv");
  ASSERT_EQ(rows.size(), 4u);
  for (const auto& row : rows) {
    EXPECT_EQ(row.strategy, "cullide");
    EXPECT_EQ(row.objects, 20);
    EXPECT_EQ(row.falseNegatives, 0u);
    EXPECT_GT(row.queries, 0u);
  }
  std::ifstream metaFile(out / "meta.json");
  const auto meta = nlohmann::json::parse(metaFile);
  // The default backend, named in every row and in meta.json with what rendered for it.
  for (const auto& row : rows) EXPECT_EQ(row.visibility, "cpu");
  EXPECT_EQ(meta["visibility"]["backend"], "cpu");
  EXPECT_FALSE(meta["visibility"]["renderer"].get<std::string>().empty());
  EXPECT_FALSE(meta.contains("gl")) << "the cpu backend opens no GL";
  EXPECT_FALSE(meta["machine"]["git_commit"].get<std::string>().empty());
  EXPECT_EQ(meta["config"]["environment"], "env3");
  // The culling options in effect: env3's hierarchy reaches ours, its axis is chosen per frame.
  const auto& ours = meta["config"]["culling"]["strategies"]["ours"];
  EXPECT_EQ(ours["hierarchy"]["leaf_triangles"], 16);
  EXPECT_EQ(ours["first_axis"], "auto");
  EXPECT_EQ(meta["config"]["culling"]["visibility"]["backend"], "cpu");

  // The wall-time breakdown: the parts are disjoint, so they fit in the wall time, and the CD
  // time it counts is the frames' own.
  const auto& t = meta["shards"][0]["wall_time"];
  const double wall = t["wall_s"], cd = t["cd_s"], sim = t["simulation_s"];
  const double truth = t["ground_truth_s"], setup = t["setup_s"];
  EXPECT_GT(cd, 0.0);
  EXPECT_GT(sim, 0.0);
  EXPECT_LE(cd + sim + truth + setup, wall);
  EXPECT_NEAR(t["harness_s"].get<double>(), wall - cd - sim, 1e-9);
  double framesCd = 0;
  for (const auto& row : rows) framesCd += row.cdMs / 1e3;
  EXPECT_NEAR(cd, framesCd, 1e-3 + 1e-3 * framesCd);
}

TEST(Cli, MalformedConfigExitsTwoWithOneLine) {
  const auto dir = tempDir("bad");
  const auto bad = dir / "bad.yaml";
  std::ofstream(bad) << "environment: env1\nbodies: [\n";
  const auto r = runCdbench("run " + bad.string() + " --out " + (dir / "out").string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_NE(r.output.find("bad.yaml"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "frames.csv"));
}

TEST(Cli, UnknownStrategyExitsTwoNamingIt) {
  const auto r = runCdbench("run " + kConfigs + "env3.yaml --strategies nosuch --out " +
                            tempDir("unknown").string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("nosuch"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("cullide"), std::string::npos) << r.output;
}

TEST(Cli, InfoPrintsTheRenderer) {
  const auto r = runCdbench("info --gl surfaceless");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("GL renderer:"), std::string::npos) << r.output;
}

}  // namespace
