// The cdbench binary end to end: a small env3 run writes frames.csv and meta.json with no false
// negative; bad input exits 2 with one line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <regex>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "harness/common/BuildCommit.h"
#include "harness/tables/FrameCsv.h"
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
  // Tori are made, not loaded: no mesh file to name.
  ASSERT_TRUE(meta["assets"].is_array());
  EXPECT_TRUE(meta["assets"].empty());
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

// meta.json names what measured (the commit the binary was built from) and, beside it, the tree
// the run was started in: a binary kept from one commit and run in another tree records both.
TEST(Cli, MetaNamesTheBuildCommitAndTheTreeTheRunStartedIn) {
  const std::string built(cdb::buildCommit());
  const std::string hex = "0123456789abcdef";
  ASSERT_TRUE(built == "unknown" || (built.size() >= 40 && built.find_first_not_of(hex) >= 40 &&
                                     (built.size() == 40 || built.substr(40) == "+dirty")))
      << built;
  const auto metaOf = [](const std::filesystem::path& out) {
    std::ifstream in(out / "meta.json");
    return nlohmann::json::parse(in);
  };
  const std::string run = "run " + kConfigs + "env3.yaml --strategies cullide --objects 10 "
                          "--frames 1 --repeats 1 --resolutions 64 --quiet --no-truth --out ";

  // A tree of its own, one commit, which is not the binary's.
  const auto tree = tempDir("commit_tree");
  const auto made = cdb::test::runShellCommand(
      "cd '" + tree.string() + "' && git init -q && git -c user.name=cdbench "
      "-c user.email=cdbench@localhost commit -q --allow-empty -m tree && git rev-parse HEAD 2>&1");
  ASSERT_EQ(made.exitCode, 0) << made.output;
  std::string treeHead = made.output;
  while (!treeHead.empty() && (treeHead.back() == '\n' || treeHead.back() == ' ')) treeHead.pop_back();
  ASSERT_EQ(treeHead.size(), 40u) << made.output;
  auto r = cdb::test::runShellCommand("cd '" + tree.string() + "' && " + CDBENCH_BINARY_DIR +
                                      "/cdbench " + run + "out 2>&1");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  auto meta = metaOf(tree / "out");
  EXPECT_EQ(meta["machine"]["git_commit"], built);
  EXPECT_EQ(meta["commit"], built);
  EXPECT_EQ(meta["machine"]["run_tree_commit"], treeHead);

  // Outside any git tree: the build commit still, the tree unknown.
  const auto bare = tempDir("commit_bare");
  r = cdb::test::runShellCommand("cd '" + bare.string() + "' && GIT_CEILING_DIRECTORIES='" +
                                 bare.parent_path().string() + "' " + CDBENCH_BINARY_DIR +
                                 "/cdbench " + run + "out 2>&1");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  meta = metaOf(bare / "out");
  EXPECT_EQ(meta["machine"]["git_commit"], built);
  EXPECT_EQ(meta["machine"]["run_tree_commit"], "unknown");
}

// The average of a cell as the table computes it: the mean over repeats of each repeat's mean.
double averageOf(const std::vector<cdb::FrameRecord>& rows, const std::string& strategy, int resolution) {
  std::map<int, std::pair<double, int>> byRepeat;
  for (const auto& r : rows)
    if (r.strategy == strategy && r.resolution == resolution) {
      byRepeat[r.repeat].first += r.cdMs;
      ++byRepeat[r.repeat].second;
    }
  double sum = 0;
  for (const auto& [repeat, s] : byRepeat) sum += s.first / s.second;
  return sum / static_cast<double>(byRepeat.size());
}

// A run ends by printing its average/maximum table on stdout (rows = detectors, columns = the
// resolutions, the false negatives, the backend), writes it as summary.md and summary.csv, and
// measures what draws nothing once per simulation; --quiet prints nothing.
TEST(Cli, ARunPrintsItsTableAndWritesItBesideTheFrames) {
  const auto out = tempDir("table");
  const std::string args = "run " + kConfigs + "env3.yaml --strategies cullide,ours,fcl --objects 20 "
                           "--frames 4 --repeats 2 --resolutions 64,128 --out " + out.string();
  const auto r = cdb::test::runShellCommand(std::string(CDBENCH_BINARY_DIR) + "/cdbench " + args +
                                            " 2>/dev/null");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto rows = cdb::readFrameCsv(out / "frames.csv");
  // fcl: one cell per simulation at no resolution, 4 frames each; the others 4 frames per
  // resolution and simulation.
  std::size_t fclRows = 0;
  for (const auto& row : rows)
    if (row.strategy == "fcl") {
      ++fclRows;
      EXPECT_EQ(row.resolution, 0);
      EXPECT_EQ(row.visibility, "-");
    }
  EXPECT_EQ(fclRows, 2u * 4);
  EXPECT_EQ(rows.size(), 2u * 4 * (2 * 2 + 1));

  for (const char* title : {"env3: average CD time per frame (ms), 20 objects, cpu backend",
                            "env3: maximum CD time per frame (ms), 20 objects, cpu backend",
                            "strategy \\ resolution", "false negatives"})
    EXPECT_NE(r.output.find(title), std::string::npos) << title << " not in:\n" << r.output;
  // Each detector's average row, its numbers those of frames.csv; fcl's in both columns.
  for (const std::string strategy : {"cullide", "ours", "fcl"}) {
    const int at64 = strategy == "fcl" ? 0 : 64, at128 = strategy == "fcl" ? 0 : 128;
    const std::regex row("\\n" + strategy + " +" + fmt::format("{:.2f}", averageOf(rows, strategy, at64)) +
                         " +" + fmt::format("{:.2f}", averageOf(rows, strategy, at128)) + " +0\\n");
    EXPECT_TRUE(std::regex_search(r.output, row)) << strategy << " row not in:\n" << r.output;
  }
  const std::string md = cdb::test::runShellCommand("cat " + (out / "summary.md").string()).output;
  EXPECT_NE(md.find("| strategy \\ resolution | 64 | 128 | false negatives |"), std::string::npos) << md;
  const std::string csv = cdb::test::runShellCommand("cat " + (out / "summary.csv").string()).output;
  EXPECT_NE(csv.find("average,ours," + fmt::format("{:.4f}", averageOf(rows, "ours", 64))), std::string::npos)
      << csv;

  const auto quiet = cdb::test::runShellCommand(std::string(CDBENCH_BINARY_DIR) + "/cdbench " + args +
                                                " --quiet 2>/dev/null");
  ASSERT_EQ(quiet.exitCode, 0);
  EXPECT_EQ(quiet.output, "");
}

// Raw mode (pixel centres, the thesis' small depth offset) is what the precision study measures:
// on env1's frame 60 (~40 touching pairs) at 32 px, CULLIDE and CIS lose contacts in raw mode and
// none in the default conservative mode, on the same recorded frames; meta.json records the mode
// and the offset. A larger --raw-offset makes CIS (whole objects, no triangle level) lose fewer:
// the offset reaches what depth loses, not what pixel coverage does.
TEST(Cli, RawModeLosesContactsConservativeModeNone) {
  const auto dir = tempDir("raw");
  const std::string poses = (dir / "env1.poses").string();
  const std::string common = "run " + kConfigs + "env1.yaml --strategies cullide,cis --resolutions 32 "
                             "--repeats 1 --frames 61 --frame-stride 60 --quiet ";
  const auto conservative = runCdbench(common + "--record " + poses + " --out " + (dir / "c").string());
  ASSERT_EQ(conservative.exitCode, 0) << conservative.output;
  const auto raw = runCdbench(common + "--raw --replay " + poses + " --out " + (dir / "r").string());
  ASSERT_EQ(raw.exitCode, 0) << raw.output;
  const auto wide = runCdbench(common + "--raw --raw-offset 0.25 --replay " + poses + " --out " +
                               (dir / "w").string());
  ASSERT_EQ(wide.exitCode, 0) << wide.output;

  const auto atFrame60 = [](const std::filesystem::path& out, const std::string& strategy) {
    for (const auto& row : cdb::readFrameCsv(out / "frames.csv"))
      if (row.frame == 60 && row.strategy == strategy) return row;
    ADD_FAILURE() << "no frame 60 of " << strategy << " in " << out;
    return cdb::FrameRecord{};
  };
  for (const std::string strategy : {"cullide", "cis"}) {
    const auto c = atFrame60(dir / "c", strategy), r = atFrame60(dir / "r", strategy);
    ASSERT_GT(c.truthPairs, 10u) << strategy;
    EXPECT_EQ(r.truthPairs, c.truthPairs) << strategy << ": the same frame";
    EXPECT_EQ(c.falseNegatives, 0u) << strategy;
    EXPECT_GT(r.falseNegatives, 0u) << strategy;
    EXPECT_LE(r.falseNegatives, r.truthPairs) << strategy;
  }
  EXPECT_LT(atFrame60(dir / "w", "cis").falseNegatives, atFrame60(dir / "r", "cis").falseNegatives);

  const auto metaOf = [](const std::filesystem::path& out) {
    std::ifstream in(out / "meta.json");
    return nlohmann::json::parse(in);
  };
  EXPECT_EQ(metaOf(dir / "c")["config"]["conservative"], true);
  EXPECT_EQ(metaOf(dir / "r")["config"]["conservative"], false);
  EXPECT_EQ(metaOf(dir / "r")["config"]["culling"]["visibility"]["raw_depth_offset"], 1e-5);
  EXPECT_EQ(metaOf(dir / "w")["config"]["culling"]["visibility"]["raw_depth_offset"], 0.25);
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

TEST(Cli, BadStrategyRepeatsExitTwoNamingTheItem) {
  for (const std::string item : {"quick_cullide", "quick_cullide=x", "quick_cullide=0",
                                 "quick_cullide=4", "nosuch=1"}) {
    const auto r = runCdbench("run " + kConfigs + "env1.yaml --repeats 3 --strategy-repeats " + item +
                              " --out " + tempDir("strategy-repeats").string());
    EXPECT_EQ(r.exitCode, 2) << item << ": " << r.output;
    EXPECT_NE(r.output.find("--strategy-repeats '" + item + "'"), std::string::npos) << r.output;
  }
}

TEST(Cli, InfoPrintsTheRenderer) {
  const auto r = runCdbench("info --gl surfaceless");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("GL renderer:"), std::string::npos) << r.output;
}

}  // namespace
