// The cpu visibility backend needs no GL: with EGL pointed at no vendor library (glvnd then finds
// no driver, as on a machine without one), `cdbench run --visibility cpu` still runs and loses no
// contact, while --visibility gl-queries fails with one line instead of crashing.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "harness/tables/FrameCsv.h"
#include "tests/common/FreshTempDir.h"
#include "tests/common/ShellCommand.h"

namespace {

// glvnd looks for EGL vendors (Mesa's 50_mesa.json, ...) only here: an empty answer means no EGL.
const std::string kNoEgl = "__EGL_VENDOR_LIBRARY_DIRS=/nonexistent ";

cdb::test::CommandResult runWithoutEgl(const std::string& backend, const std::filesystem::path& out) {
  return cdb::test::runShellCommand(
      kNoEgl + std::string(CDBENCH_BINARY_DIR) + "/cdbench run " + CDBENCH_SOURCE_DIR +
      "/configs/env3.yaml --strategies cullide,ours --objects 20 --frames 4 --repeats 1 "
      "--resolutions 64,256 --quiet --visibility " + backend + " --out " + out.string() + " 2>&1");
}

TEST(CpuBackendWithoutGl, RunsWithNoFalseNegatives) {
  const auto out = cdb::test::freshTempDir("nogl_cpu");
  const auto r = runWithoutEgl("cpu", out);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto rows = cdb::readFrameCsv(out / "frames.csv");
  ASSERT_EQ(rows.size(), 16u);  // 2 strategies x 2 resolutions x 4 frames
  for (const auto& row : rows) {
    EXPECT_EQ(row.visibility, "cpu");
    EXPECT_EQ(row.falseNegatives, 0u) << row.strategy << " frame " << row.frame;
    EXPECT_GT(row.queries, 0u);
  }
}

TEST(CpuBackendWithoutGl, GlQueriesFailCleanlyThere) {
  const auto out = cdb::test::freshTempDir("nogl_gl");
  const auto r = runWithoutEgl("gl-queries", out);
  EXPECT_EQ(r.exitCode, 1) << r.output;  // a RunError, not a crash
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out / "frames.csv"));
}

}  // namespace
