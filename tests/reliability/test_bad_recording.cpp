// Bad pose recordings given to --replay: exit 2, one line naming the recording and what is wrong,
// no result file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/reliability/CdbenchProcess.h"

namespace cdb::test {
namespace {

class BadRecording : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scratch_ = new ScratchDir;
    const auto r = runCdbench(smallRun(
        kEnv3, scratch_->path() / "recorded",
        {"--objects", "4", "--resolutions", "64", "--no-truth", "--record", recording().string()}));
    ASSERT_EQ(r.exitCode, 0) << r.stdErr;
  }
  static void TearDownTestSuite() {
    delete scratch_;
    scratch_ = nullptr;
  }
  // A good recording of env3 with 4 tori and 2 frames.
  static std::filesystem::path recording() { return scratch_->path() / "env3-4.poses"; }

  ScratchDir dir;
  std::filesystem::path out() const { return dir.path() / "out"; }
  ProcessResult replay(const std::filesystem::path& file, const std::string& objects = "4") const {
    return runCdbench(smallRun(
        kEnv3, out(),
        {"--objects", objects, "--resolutions", "64", "--no-truth", "--replay", file.string()}));
  }
  std::filesystem::path copyOfRecording(std::uintmax_t keepBytes) const {
    const auto file = dir.path() / "copy.poses";
    std::filesystem::copy_file(recording(), file);
    std::filesystem::resize_file(file, keepBytes);
    return file;
  }

 private:
  static ScratchDir* scratch_;
};

ScratchDir* BadRecording::scratch_ = nullptr;

// The replay path itself works: only what each test breaks is wrong.
TEST_F(BadRecording, TheGoodRecordingReplays) {
  const auto r = replay(recording());
  ASSERT_EQ(r.exitCode, 0) << r.stdErr;
  for (const char* f : kResultFiles) EXPECT_TRUE(std::filesystem::exists(out() / f)) << f;
}

TEST_F(BadRecording, FromAnotherConfig) {
  const auto r = replay(recording(), "5");
  expectCleanFailure(r, 2, out(), {recording().string(), "another config"});
}

TEST_F(BadRecording, TruncatedInThePoses) {
  const auto size = std::filesystem::file_size(recording());
  const auto file = copyOfRecording(size - 20);
  const auto r = replay(file);
  expectCleanFailure(r, 2, out(), {file.string(), "truncated", "expected 2 frames of 4 objects"});
}

// The recording is checked before the output folder is claimed: the failed run leaves no run.json,
// and the corrected command then runs into the same --out.
TEST_F(BadRecording, TheCorrectedReplayRunsIntoTheSameFolder) {
  const auto file = copyOfRecording(std::filesystem::file_size(recording()) - 20);
  expectCleanFailure(replay(file), 2, out(), {file.string(), "truncated"});
  EXPECT_FALSE(std::filesystem::exists(out() / "run.json"));
  const auto r = replay(recording());
  ASSERT_EQ(r.exitCode, 0) << r.stdErr;
  for (const char* f : kResultFiles) EXPECT_TRUE(std::filesystem::exists(out() / f)) << f;
}

TEST_F(BadRecording, TruncatedInTheHeader) {
  const auto file = copyOfRecording(10);
  const auto r = replay(file);
  expectCleanFailure(r, 2, out(), {file.string(), "truncated"});
}

TEST_F(BadRecording, NotARecording) {
  const auto file = dir.write("config.poses", "environment: env3\n");
  const auto r = replay(file);
  expectCleanFailure(r, 2, out(), {file.string(), "not a pose recording"});
}

TEST_F(BadRecording, Missing) {
  const auto file = dir.path() / "nosuch.poses";
  const auto r = replay(file);
  expectCleanFailure(r, 2, out(), {file.string(), "cannot open"});
}

TEST_F(BadRecording, CorruptedPoseData) {
  const auto file = dir.path() / "flipped.poses";
  std::filesystem::copy_file(recording(), file);
  {
    std::fstream f(file, std::ios::binary | std::ios::in | std::ios::out);
    // The lowest byte of the last pose's rotation z: a change far below any plausibility
    // check, which only the checksum sees.
    char low = 0;
    f.seekg(-8, std::ios::end);
    f.get(low);
    f.seekp(-8, std::ios::end);
    f.put(static_cast<char>(low ^ 0x01));
  }
  const auto r = replay(file);
  expectCleanFailure(r, 2, out(), {file.string(), "checksum"});
}

}  // namespace
}  // namespace cdb::test
