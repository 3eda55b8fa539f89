// Bad input to `cdbench snapshot`: exit 2, one line on stderr naming the option and what was
// expected, and nothing written where the picture would go (no PNG, no JSON, no temporary file).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/reliability/CdbenchProcess.h"

namespace cdb::test {
namespace {

class BadSnapshot : public ::testing::Test {
 protected:
  ScratchDir dir;
  std::filesystem::path out() const { return dir.path() / "out"; }

  // A snapshot of env3 with 4 tori at frame 1 into out()/s.png, with `extra` options (an option
  // given here replaces the default one).
  ProcessResult snapshot(const std::vector<std::string>& extra,
                         const std::string& config = kEnv3) const {
    std::vector<std::string> args = {"snapshot", config, "--objects", "4"};
    const auto has = [&](const std::string& option) {
      return std::find(extra.begin(), extra.end(), option) != extra.end();
    };
    if (!has("--size")) args.insert(args.end(), {"--size", "320x240"});
    if (!has("--frame") && !has("--frames")) args.insert(args.end(), {"--frame", "1"});
    if (!has("--out")) args.insert(args.end(), {"--out", (out() / "s.png").string()});
    args.insert(args.end(), extra.begin(), extra.end());
    return runCdbench(args);
  }

  // The clean-failure contract, and the output folder holds nothing.
  void expectRefused(const ProcessResult& r, const std::vector<std::string>& mentions) const {
    expectCleanFailure(r, 2, out(), mentions);
    if (!std::filesystem::exists(out())) return;
    for (const auto& e : std::filesystem::recursive_directory_iterator(out())) {
      EXPECT_TRUE(e.is_directory()) << e.path() << " left behind";
    }
  }
};

// The command itself works: only what each test breaks is wrong.
TEST_F(BadSnapshot, TheGoodCommandWritesThePicture) {
  const auto r = snapshot({});
  ASSERT_EQ(r.exitCode, 0) << r.stdErr;
  EXPECT_TRUE(std::filesystem::exists(out() / "s.png"));
  EXPECT_TRUE(std::filesystem::exists(out() / "s.json"));
}

TEST_F(BadSnapshot, FramePastTheSimulationsEnd) {
  expectRefused(snapshot({"--frame", "300"}),
                {"--frame 300", "past the simulation's end", "0..299"});
}

TEST_F(BadSnapshot, FrameRangePastTheSimulationsEnd) {
  expectRefused(snapshot({"--frames", "280:310:10", "--out", (out() / "a.gif").string()}),
                {"--frames 280:310:10", "frame 300", "past the simulation's end"});
}

TEST_F(BadSnapshot, FramePastTheRecordingsEnd) {
  const auto recording = dir.path() / "two.poses";
  const auto made = runCdbench(smallRun(
      kEnv3, dir.path() / "run",
      {"--objects", "4", "--resolutions", "64", "--no-truth", "--record", recording.string()}));
  ASSERT_EQ(made.exitCode, 0) << made.stdErr;
  expectRefused(snapshot({"--replay", recording.string(), "--frame", "2"}),
                {"--frame 2", recording.string(), "frames 0..1"});
}

TEST_F(BadSnapshot, NegativeFrame) {
  expectRefused(snapshot({"--frame", "-1"}), {"--frame -1", ">= 0"});
}

TEST_F(BadSnapshot, NeitherOrBothFrameOptions) {
  expectRefused(snapshot({"--frames", "0:3:1", "--frame", "1"}),
                {"--frame", "--frames", "exactly one"});
}

TEST_F(BadSnapshot, UnknownStrategy) {
  expectRefused(snapshot({"--strategy", "nosuch"}), {"--strategy", "nosuch", "cullide"});
}

TEST_F(BadSnapshot, UnknownView) {
  expectRefused(snapshot({"--view", "diagonal"}), {"--view", "diagonal", "x, y, z or iso"});
}

TEST_F(BadSnapshot, UnknownBackend) {
  expectRefused(snapshot({"--strategy", "ours", "--visibility", "nosuch"}),
                {"--visibility", "nosuch"});
}

TEST_F(BadSnapshot, SizeOfZero) {
  expectRefused(snapshot({"--size", "0x240"}), {"--size", "0x240", "WxH"});
}

TEST_F(BadSnapshot, SizeOf100000) {
  expectRefused(snapshot({"--size", "100000x240"}), {"--size", "100000x240", "2048"});
}

TEST_F(BadSnapshot, ResolutionOf0And100000) {
  expectRefused(snapshot({"--strategy", "ours", "--resolution", "0"}),
                {"--resolution 0", "1..16384"});
  expectRefused(snapshot({"--strategy", "ours", "--resolution", "100000"}),
                {"--resolution 100000"});
}

TEST_F(BadSnapshot, UnwritableOutputPath) {
  // A folder cannot be made under a regular file, whoever runs the test (root included).
  const auto file = dir.write("plain-file", "not a folder");
  const auto target = (file / "s.png").string();
  expectRefused(snapshot({"--out", target}), {"--out " + target, "cannot create the folder"});
  EXPECT_EQ(std::filesystem::file_size(file), 12u);
}

TEST_F(BadSnapshot, OutputThatIsAFolder) {
  std::filesystem::create_directories(out() / "s.png");
  expectRefused(snapshot({}), {"--out", "is a folder"});
}

TEST_F(BadSnapshot, OutputOfTheWrongKind) {
  expectRefused(snapshot({"--out", (out() / "s.jpg").string()}), {"--out", "s.jpg", ".png"});
  expectRefused(snapshot({"--frames", "0:3:1", "--out", (out() / "s.png").string()}),
                {"--out", ".gif or"});
}

TEST_F(BadSnapshot, ObjectsForAConfigWithoutACountedGroup) {
  expectRefused(snapshot({}, kConfigDir + "env1.yaml"), {"env1.yaml", "counted_group"});
}

}  // namespace
}  // namespace cdb::test
