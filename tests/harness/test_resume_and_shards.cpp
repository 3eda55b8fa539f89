// Interrupted runs keep their finished cells and resume without redoing them; shards run with
// GNU parallel and merged give the same frames as one unsharded run; balanced shares (--balance)
// take over the cells no other share has started and measure each cell once.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/run/CellClaim.h"
#include "harness/run/RunPlan.h"
#include "harness/tables/FrameCsv.h"
#include "tests/common/ShellCommand.h"

namespace fs = std::filesystem;

namespace {

const std::string kBinary = std::string(CDBENCH_BINARY_DIR) + "/cdbench";
const std::string kEnv3 = std::string(CDBENCH_SOURCE_DIR) + "/configs/env3.yaml";

// A small env3 sweep: 2 counts x 2 repeats x 2 strategies x 2 resolutions = 16 cells.
std::vector<std::string> sweepArgs(const fs::path& out) {
  return {kBinary, "run", kEnv3, "--strategies", "cullide,sorted", "--objects", "12,16",
          "--repeats", "2", "--frames", "4", "--resolutions", "64,96", "--quiet",
          "--out", out.string()};
}

fs::path freshDir(const std::string& name) {
  // One folder per process: two test runs at once on one machine do not share it.
  const auto dir =
      fs::temp_directory_path() / ("cdbench_resume_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(dir);
  return dir;
}

pid_t spawn(const std::vector<std::string>& args) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    std::_Exit(127);
  }
  return pid;
}

int waitExit(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return -1;
}

int run(const std::vector<std::string>& args) { return waitExit(spawn(args)); }

std::size_t cellCount(const fs::path& out) {
  std::size_t n = 0;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(out / "cells", ec)) n += e.path().extension() == ".csv";
  return n;
}

// Waits until at least `cells` cells are finished, then stops the run with `signal`.
int interruptAfter(const fs::path& out, std::size_t cells, int signal) {
  const pid_t pid = spawn(sweepArgs(out));
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (cellCount(out) < cells && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ::kill(pid, signal);
  return waitExit(pid);
}

std::map<std::string, fs::file_time_type> cellTimes(const fs::path& out) {
  std::map<std::string, fs::file_time_type> times;
  for (const auto& e : fs::directory_iterator(out / "cells"))
    times[e.path().filename().string()] = fs::last_write_time(e.path());
  return times;
}

// Everything but the timings: what the strategies answered on which frames.
std::string answers(const fs::path& framesCsv) {
  std::ostringstream s;
  for (const auto& r : cdb::readFrameCsv(framesCsv))
    s << r.environment << ' ' << r.strategy << ' ' << r.resolution << ' ' << r.objects << ' '
      << r.repeat << ' ' << r.frame << ' ' << r.pcsSize << ' ' << r.sets << ' ' << r.pcsTriangles
      << ' ' << r.pairsTested << ' ' << r.collidingPairs << ' ' << r.truthPairs << ' '
      << r.falseNegatives << ' ' << r.queries << ' ' << r.draws << '\n';
  return s.str();
}

void expectResumesWithoutRedoing(const fs::path& out) {
  const std::size_t kept = cellCount(out);
  ASSERT_GT(kept, 0u);
  ASSERT_LT(kept, 16u) << "the run finished before it could be interrupted";
  EXPECT_FALSE(fs::exists(out / "frames.csv")) << "an interrupted run must not look complete";
  EXPECT_FALSE(fs::exists(out / "meta.json"));
  const auto before = cellTimes(out);

  ASSERT_EQ(run(sweepArgs(out)), 0);
  EXPECT_EQ(cellCount(out), 16u);
  const auto after = cellTimes(out);
  for (const auto& [name, time] : before) EXPECT_EQ(after.at(name), time) << name << " was redone";
  EXPECT_EQ(cdb::readFrameCsv(out / "frames.csv").size(), 16u * 4);
}

TEST(Resume, SigtermFinishesTheFrameKeepsFinishedCellsAndTheSameCommandResumes) {
  const auto out = freshDir("term");
  EXPECT_EQ(interruptAfter(out, 3, SIGTERM), 128 + SIGTERM);
  expectResumesWithoutRedoing(out);
}

TEST(Resume, SigkillLosesAtMostTheCellInProgress) {
  const auto out = freshDir("kill");
  EXPECT_EQ(interruptAfter(out, 5, SIGKILL), 128 + SIGKILL);
  // No half-written cell: every cell left is complete, 4 frames. A kill between a cell's temporary
  // file and its rename leaves that file (CELL.csv.tmp.PID), which no run reads as a cell.
  for (const auto& e : fs::directory_iterator(out / "cells")) {
    if (e.path().filename().string().find(".csv.tmp.") != std::string::npos) continue;
    ASSERT_EQ(e.path().extension(), ".csv") << e.path();
    EXPECT_EQ(cdb::readFrameCsv(e.path()).size(), 4u) << e.path();
  }
  expectResumesWithoutRedoing(out);
}

TEST(Resume, AnotherConfigInTheSameFolderIsRefused) {
  const auto out = freshDir("other");
  auto args = sweepArgs(out);
  args[6] = "12";  // --objects 12 only: a sub-sweep of the same run is fine
  ASSERT_EQ(run(args), 0);
  auto other = sweepArgs(out);
  other.insert(other.end(), {"--seed", "99"});
  EXPECT_EQ(run(other), 2);
}

// A one-simulation env3 run of 2 cells, as one shell command line.
std::string smallRunCommand(const fs::path& out) {
  return kBinary + " run " + kEnv3 + " --strategies cullide --objects 8 --repeats 1 --frames 3 " +
         "--resolutions 64,96 --quiet --out " + out.string() + " 2>&1";
}

// What a run that failed before finishing a cell leaves (run.json naming another run) does not
// keep the next run out of the folder.
TEST(Resume, AFolderWithoutFinishedCellsNeverBlocksANewRun) {
  const auto out = freshDir("unfinished");
  fs::create_directories(out / "cells");
  std::ofstream(out / "run.json") << R"({"environment": "env1", "identity": "0123456789abcdef",
                                          "config": "configs/env1.yaml", "config_text": "", "plan": []})";
  const auto r = cdb::test::runShellCommand(smallRunCommand(out));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(cellCount(out), 2u);
  EXPECT_TRUE(fs::exists(out / "frames.csv"));
  std::ifstream identity(out / "run.json");
  EXPECT_EQ(nlohmann::json::parse(identity)["environment"], "env3");
}

// Cells kept from a run of another build are resumed (a rebuild changes no answer) with a note
// naming that build, since their times are its; run.json keeps every build that measured cells.
TEST(Resume, CellsOfAnotherBuildAreNamedWhenResumed) {
  const auto out = freshDir("otherbuild");
  const auto first = cdb::test::runShellCommand(smallRunCommand(out));
  ASSERT_EQ(first.exitCode, 0) << first.output;
  EXPECT_EQ(first.output.find("another build"), std::string::npos) << first.output;
  auto identity = nlohmann::json::parse(std::ifstream(out / "run.json"));
  ASSERT_EQ(identity["builds"].size(), 1u);
  const std::string thisBuild = identity["builds"][0];
  // The same build again: resumed without a note.
  const auto same = cdb::test::runShellCommand(smallRunCommand(out));
  ASSERT_EQ(same.exitCode, 0) << same.output;
  EXPECT_NE(same.output.find("2 resumed"), std::string::npos) << same.output;
  EXPECT_EQ(same.output.find("another build"), std::string::npos) << same.output;
  // As if an older build had measured them.
  identity["builds"] = {"0123abc"};
  std::ofstream(out / "run.json", std::ios::trunc) << identity.dump(2);
  const auto other = cdb::test::runShellCommand(smallRunCommand(out));
  ASSERT_EQ(other.exitCode, 0) << other.output;
  for (const std::string& part : {std::string("2 resumed cells"), std::string("another build (0123abc)"),
                                  thisBuild, "delete " + out.string() + "/cells"})
    EXPECT_NE(other.output.find(part), std::string::npos) << part << " not in: " << other.output;
  identity = nlohmann::json::parse(std::ifstream(out / "run.json"));
  EXPECT_EQ(identity["builds"], nlohmann::json::array({"0123abc", thisBuild}));
}

// A damaged cell stops the resumed run before it measures anything, named with its line and with
// how to measure it again; doing what the message says finishes the run.
TEST(Resume, ADamagedCellIsNamedWithItsLineAndHowToMeasureItAgain) {
  const auto out = freshDir("damaged");
  ASSERT_EQ(cdb::test::runShellCommand(smallRunCommand(out)).exitCode, 0);
  const fs::path cell = out / "cells" / "o8_r0_cullide_96.csv";
  ASSERT_TRUE(fs::exists(cell));
  std::string text;
  {
    std::ifstream in(cell);
    std::ostringstream s;
    s << in.rdbuf();
    text = s.str();
  }
  // The third line (second frame) cut after its fourth field.
  const auto second = text.find('\n', text.find('\n') + 1) + 1;
  std::size_t cut = second;
  for (int commas = 0; commas < 4; ++cut) commas += text[cut] == ',';
  std::ofstream(cell, std::ios::trunc) << text.substr(0, cut) << "\n" << text.substr(text.find('\n', second) + 1);

  const auto refused = cdb::test::runShellCommand(smallRunCommand(out));
  EXPECT_EQ(refused.exitCode, 2) << refused.output;
  EXPECT_EQ(std::count(refused.output.begin(), refused.output.end(), '\n'), 1) << refused.output;
  for (const std::string& part :
       std::vector<std::string>{cell.string() + ":3:", "delete " + cell.string(), "run the same command again"})
    EXPECT_NE(refused.output.find(part), std::string::npos) << part << " not in: " << refused.output;

  fs::remove(cell);
  const auto again = cdb::test::runShellCommand(smallRunCommand(out));
  ASSERT_EQ(again.exitCode, 0) << again.output;
  EXPECT_EQ(cdb::readFrameCsv(cell).size(), 3u);
  EXPECT_EQ(cdb::readFrameCsv(out / "frames.csv").size(), 6u);
}

TEST(Shards, GnuParallelShardsMergedEqualTheUnshardedRun) {
  if (std::system("command -v parallel >/dev/null 2>&1") != 0) GTEST_SKIP() << "GNU parallel missing";
  const auto whole = freshDir("whole");
  ASSERT_EQ(run(sweepArgs(whole)), 0);

  const auto base = freshDir("shards");
  fs::create_directories(base);
  std::string cmd = "parallel --will-cite --halt now,fail=1 -j 3 '" + kBinary + " run " + kEnv3 +
                    " --strategies cullide,sorted --objects 12,16 --repeats 2 --frames 4"
                    " --resolutions 64,96 --quiet --shard {}/3 --out " + base.string() +
                    "/s{}' ::: 1 2 3";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  for (int i = 1; i <= 3; ++i) EXPECT_FALSE(fs::exists(base / ("s" + std::to_string(i)) / "frames.csv"));

  const auto merged = base / "merged";
  ASSERT_EQ(run({kBinary, "merge", "--out", merged.string(), (base / "s1").string(),
                 (base / "s2").string(), (base / "s3").string()}),
            0);
  EXPECT_EQ(answers(merged / "frames.csv"), answers(whole / "frames.csv"));
  EXPECT_TRUE(fs::exists(merged / "meta.json"));
  // The merged meta.json records the culling options in effect, as one run's does.
  std::ifstream mergedMeta(merged / "meta.json"), wholeMeta(whole / "meta.json");
  const auto mergedCulling = nlohmann::json::parse(mergedMeta)["config"]["culling"];
  EXPECT_TRUE(mergedCulling.is_object());
  EXPECT_EQ(mergedCulling, nlohmann::json::parse(wholeMeta)["config"]["culling"]);

  // Two shards only: the merge names what is missing and writes nothing.
  const auto partial = base / "partial";
  EXPECT_EQ(run({kBinary, "merge", "--out", partial.string(), (base / "s1").string(),
                 (base / "s2").string()}),
            2);
  EXPECT_FALSE(fs::exists(partial / "frames.csv"));
}

// A command line of `args` (none holds a space or quote) with stderr joined to stdout.
std::string commandLine(const std::vector<std::string>& args) {
  std::string line;
  for (const auto& a : args) line += a + " ";
  return line + "2>&1";
}

std::vector<std::string> balancedShare(const fs::path& out, int share, int shares) {
  auto args = sweepArgs(out);
  for (const char* a : {"--balance", "--shard"}) args.emplace_back(a);
  args.push_back(std::to_string(share) + "/" + std::to_string(shares));
  return args;
}

// "N cells measured" summed over every line of `output` that says it.
std::size_t cellsMeasured(const std::string& output) {
  std::size_t sum = 0;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    const auto at = line.find(" cells measured");
    if (at == std::string::npos) continue;
    const auto start = line.find_last_not_of("0123456789", at - 1) + 1;
    sum += std::stoul(line.substr(start, at - start));
  }
  return sum;
}

TEST(BalancedShards, AShareAloneTakesOverEveryCellNoOtherShareStarted) {
  const auto whole = freshDir("balanced_whole");
  ASSERT_EQ(run(sweepArgs(whole)), 0);
  const auto out = freshDir("balanced_alone");
  const auto first = cdb::test::runShellCommand(commandLine(balancedShare(out, 1, 2)));
  ASSERT_EQ(first.exitCode, 0) << first.output;
  // Its own 8 of the 16 cells, then share 2's: the run is whole and says so.
  EXPECT_NE(first.output.find("16 cells measured, 0 resumed; 8 of them taken over"),
            std::string::npos)
      << first.output;
  EXPECT_EQ(answers(out / "frames.csv"), answers(whole / "frames.csv"));
  EXPECT_FALSE(fs::exists(out / "claims"));
  // Share 2, started after, finds its cells finished.
  const auto second = cdb::test::runShellCommand(commandLine(balancedShare(out, 2, 2)));
  ASSERT_EQ(second.exitCode, 0) << second.output;
  EXPECT_NE(second.output.find("0 cells measured, 8 resumed"), std::string::npos) << second.output;
}

TEST(BalancedShards, SharesStartedTogetherMeasureEachCellOnce) {
  const auto whole = freshDir("balanced_whole2");
  ASSERT_EQ(run(sweepArgs(whole)), 0);
  const auto out = freshDir("balanced_together");
  const std::string both = "( " + commandLine(balancedShare(out, 1, 2)) + " & " +
                           commandLine(balancedShare(out, 2, 2)) + " & wait )";
  const auto r = cdb::test::runShellCommand(both);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(cellsMeasured(r.output), 16u) << r.output;
  if (!fs::exists(out / "frames.csv")) {  // both finished at once: the merge writes it
    ASSERT_EQ(run({kBinary, "merge", "--out", out.string(), out.string()}), 0);
  }
  EXPECT_EQ(answers(out / "frames.csv"), answers(whole / "frames.csv"));
}

TEST(BalancedShards, ACellClaimedElsewhereIsLeftToItsHolder) {
  const auto out = freshDir("balanced_claimed");
  fs::create_directories(out);
  const std::string key = cdb::Cell{16, 1, "sorted", 96}.key();
  auto held = cdb::CellClaim::take(out, key);
  ASSERT_TRUE(held.has_value());
  const auto first = cdb::test::runShellCommand(commandLine(balancedShare(out, 1, 1)));
  ASSERT_EQ(first.exitCode, 0) << first.output;
  EXPECT_NE(first.output.find("shard done: 15 cells measured"), std::string::npos) << first.output;
  EXPECT_FALSE(fs::exists(out / "cells" / (key + ".csv")));
  EXPECT_FALSE(fs::exists(out / "frames.csv"));
  held.reset();  // its holder gave up without measuring it: the next run does
  const auto again = cdb::test::runShellCommand(commandLine(balancedShare(out, 1, 1)));
  ASSERT_EQ(again.exitCode, 0) << again.output;
  EXPECT_NE(again.output.find("1 cells measured, 15 resumed"), std::string::npos) << again.output;
  EXPECT_TRUE(fs::exists(out / "frames.csv"));
}

}  // namespace
