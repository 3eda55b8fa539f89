// Failures while running: an output folder that cannot be written, dynamics that explode, no EGL
// at all. Exit 1, one line naming what failed, no result file, never a crash.
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/reliability/CdbenchProcess.h"

namespace cdb::test {
namespace {

class BadEnvironment : public ::testing::Test {
 protected:
  ScratchDir dir;
  std::filesystem::path out() const { return dir.path() / "out"; }
};

// A path below a regular file cannot be created by anyone, root included.
TEST_F(BadEnvironment, OutputFolderBelowAFile) {
  const auto file = dir.write("file", "x");
  const auto target = file / "results";
  const auto r = runCdbench(smallRun(kEnv3, target, {"--objects", "3", "--resolutions", "64"}));
  expectCleanFailure(r, 1, target, {target.string(), "output folder"});
  EXPECT_TRUE(std::filesystem::is_regular_file(file));
}

TEST_F(BadEnvironment, OutputFolderIsAFile) {
  const auto file = dir.write("file", "x");
  const auto r = runCdbench(smallRun(kEnv3, file, {"--objects", "3", "--resolutions", "64"}));
  ASSERT_EQ(r.signal, 0) << r.stdErr;
  EXPECT_EQ(r.exitCode, 1) << r.stdErr;
  EXPECT_EQ(std::count(r.stdErr.begin(), r.stdErr.end(), '\n'), 1) << r.stdErr;
  EXPECT_NE(r.stdErr.find(file.string()), std::string::npos) << r.stdErr;
}

// One-second steps at the largest accepted speed, no container: the first frame throws the bodies
// past any sane distance, and the run stops there instead of culling nonsense poses.
TEST_F(BadEnvironment, UnstableSimulationNamesTheFrameAndTheBody) {
  const auto config =
      dir.write("unstable.yaml",
                "environment: unstable\n"
                "dynamics: {gravity: [0, 0, 0], time_step: 1.0, steps_per_frame: 10, frames: 20,\n"
                "           container_half_extent: 0}\n"
                "bodies:\n"
                "  - name: rockets\n"
                "    mesh: {kind: torus}\n"
                "    count: 3\n"
                "    placement: {region_min: [-2, -2, -2], region_max: [2, 2, 2],\n"
                "                speed_min: 10000, speed_max: 10000}\n"
                "sweep: {resolutions: [64], strategies: [cullide]}\n");
  const auto r = runCdbench({"run", config.string(), "--quiet", "--out", out().string()});
  expectCleanFailure(r, 1, out(), {"frame 1", "body ", "rockets", "unstable", "time_step"});
}

// Tori packed in a small box, flung at each other with steps far too long: the contact solver
// pushes them apart with ever larger impulses until a body leaves every bound.
TEST_F(BadEnvironment, ExplodingContactsStopTheRun) {
  const auto config =
      dir.write("explode.yaml",
                "environment: explode\n"
                "dynamics: {gravity: [0, 0, 0], time_step: 0.5, steps_per_frame: 10, frames: 200,\n"
                "           container_half_extent: 2, restitution: 1.0}\n"
                "bodies:\n"
                "  - name: tori\n"
                "    mesh: {kind: torus}\n"
                "    count: 6\n"
                "    placement: {region_min: [-1.2, -1.2, -1.2], region_max: [1.2, 1.2, 1.2],\n"
                "                speed_min: 9000, speed_max: 10000, angular_speed_max: 1000}\n"
                "sweep: {resolutions: [64], strategies: [cullide]}\n");
  const auto r = runCdbench({"run", config.string(), "--quiet", "--out", out().string()});
  expectCleanFailure(r, 1, out(), {"frame ", "body ", "tori", "unstable"});
}

// glvnd finds no vendor library: no EGL display at all. One line with the hint, no crash.
// A run on a GL backend where EGL finds no vendor (the cpu backend needs none:
// tests/harness/test_cpu_backend_without_gl.cpp).
TEST_F(BadEnvironment, NoEglVendor) {
  const std::vector<std::string> noEgl = {"__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json",
                                          "__EGL_VENDOR_LIBRARY_DIRS=/nonexistent"};
  const auto r = runCdbench(
      smallRun(kEnv3, out(), {"--objects", "3", "--resolutions", "64", "--visibility", "gl-queries"}),
      noEgl);
  expectCleanFailure(r, 1, out(), {"EGL", "install Mesa's EGL", "libegl-mesa0"});
}

// `cdbench info` says why GL does not open, on one line, and that the cpu backend still works.
TEST_F(BadEnvironment, NoEglVendorForEachPlatform) {
  const std::vector<std::string> noEgl = {"__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json",
                                          "__EGL_VENDOR_LIBRARY_DIRS=/nonexistent"};
  for (const char* platform : {"surfaceless", "device", "auto"}) {
    const auto r = runCdbench({"info", "--gl", platform}, noEgl);
    ASSERT_EQ(r.signal, 0) << r.stdErr;
    EXPECT_EQ(r.exitCode, 0) << r.stdErr;
    const auto line = [&](std::string_view start) {
      const auto at = r.stdOut.find(start);
      return at == std::string::npos ? std::string()
                                     : r.stdOut.substr(at, r.stdOut.find('\n', at) - at);
    };
    const std::string gl = line("GL:");
    EXPECT_NE(gl.find("not available"), std::string::npos) << r.stdOut;
    EXPECT_NE(gl.find("install Mesa's EGL"), std::string::npos) << r.stdOut;
    EXPECT_NE(line("  cpu").find("works"), std::string::npos) << r.stdOut;
    EXPECT_NE(line("  gl-queries").find("unavailable"), std::string::npos) << r.stdOut;
  }
}

// EGL_PLATFORM names the default platform glvnd and Mesa fall back to; a bogus one must not
// crash the fallback path either (it may still find llvmpipe through the surfaceless platform).
TEST_F(BadEnvironment, BogusEglPlatformVariable) {
  const auto r = runCdbench({"info"}, {"EGL_PLATFORM=nonsense"});
  ASSERT_EQ(r.signal, 0) << r.stdErr;
  EXPECT_TRUE(r.exitCode == 0 || r.exitCode == 1) << r.exitCode << ": " << r.stdErr;
  if (r.exitCode == 1) {
    EXPECT_EQ(std::count(r.stdErr.begin(), r.stdErr.end(), '\n'), 1) << r.stdErr;
  }
}

}  // namespace
}  // namespace cdb::test
