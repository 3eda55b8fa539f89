// Bad configs and bad command-line values: exit 2, one line naming the file or option, the key and
// what was expected, and no result file.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "culling/visibility/GlOcclusionQueryBackend.h"
#include "render/HeadlessGlContext.h"
#include "scenes/ConfigLimits.h"
#include "tests/reliability/CdbenchProcess.h"

namespace cdb::test {
namespace {

std::string shippedConfig(const std::string& name) {
  std::ifstream in(kConfigDir + name, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// env3 with one line replaced (the line must exist: the test is wrong otherwise).
std::string env3With(const std::string& pattern, const std::string& replacement) {
  const std::string text = shippedConfig("env3.yaml");
  const std::regex re(pattern, std::regex::multiline);
  EXPECT_TRUE(std::regex_search(text, re)) << pattern;
  return std::regex_replace(text, re, replacement);
}

class BadConfig : public ::testing::Test {
 protected:
  ScratchDir dir;
  std::filesystem::path out() const { return dir.path() / "out"; }
  ProcessResult run(const std::string& config, std::initializer_list<std::string> extra = {}) {
    return runCdbench(smallRun(config, out(), extra));
  }
  ProcessResult runText(const std::string& name, const std::string& text,
                        std::initializer_list<std::string> extra = {}) {
    return run(dir.write(name, text).string(), extra);
  }
};

TEST_F(BadConfig, MissingFile) {
  const auto r = run((dir.path() / "nosuch.yaml").string());
  expectCleanFailure(r, 2, out(),
                     {"nosuch.yaml", "expected a readable scenario file", "no such file"});
}

TEST_F(BadConfig, DirectoryInsteadOfFile) {
  const auto r = run(dir.path().string());
  expectCleanFailure(r, 2, out(), {dir.path().string(), "a directory"});
}

TEST_F(BadConfig, EmptyFile) {
  const auto r = runText("empty.yaml", "");
  expectCleanFailure(r, 2, out(), {"empty.yaml:1:", "expected a scenario map", "empty file"});
}

TEST_F(BadConfig, MalformedYaml) {
  const auto r = runText("malformed.yaml", "environment: env1\nbodies: [\n  {name: a\n");
  expectCleanFailure(r, 2, out(), {"malformed.yaml:", "expected valid YAML"});
}

TEST_F(BadConfig, TabIndentedYaml) {
  const auto r = runText("tabs.yaml", "environment: env1\nbodies:\n\t- name: a\n");
  expectCleanFailure(r, 2, out(), {"tabs.yaml:", "expected valid YAML"});
}

TEST_F(BadConfig, NotAMap) {
  const auto r = runText("list.yaml", "- environment\n- env1\n");
  expectCleanFailure(r, 2, out(), {"list.yaml:1:", "expected"});
}

TEST_F(BadConfig, UnknownTopLevelKey) {
  const auto r = runText("unknown.yaml", env3With("^seed: 1.*$", "seed: 1\nsede: 2"));
  expectCleanFailure(r, 2, out(), {"unknown.yaml:14:", "sede", "expected a known key"});
}

TEST_F(BadConfig, UnknownNestedKey) {
  const auto r = runText("nested.yaml", env3With("^  friction: .*$", "  fricton: 0.3"));
  expectCleanFailure(r, 2, out(), {"nested.yaml:", "dynamics.fricton", "expected a known key"});
}

TEST_F(BadConfig, UnknownStrategyOnTheCommandLine) {
  const auto r = run(kConfigDir + "env3.yaml", {"--strategies", "cullide,nosuch"});
  expectCleanFailure(r, 2, out(), {"nosuch", "expected one of", "cullide"});
}

// No --strategies: the config's own list is what is wrong, so the message names the config.
TEST_F(BadConfig, UnknownStrategyInTheConfig) {
  const auto config =
      dir.write("strategy.yaml", env3With("^  strategies: .*$", "  strategies: [cullide, nosuch]"));
  const auto r = runCdbench({"run", config.string(), "--quiet", "--out", out().string()});
  expectCleanFailure(r, 2, out(), {"strategy.yaml", "nosuch", "cullide"});
}

TEST_F(BadConfig, WrongTypeString) {
  const auto r = runText("type.yaml", env3With("^seed: 1.*$", "seed: one"));
  expectCleanFailure(r, 2, out(), {"type.yaml:13:", "seed", "expected an integer", "'one'"});
}

TEST_F(BadConfig, WrongTypeListForNumber) {
  const auto r = runText("type.yaml", env3With("^  time_step: .*$", "  time_step: [0.005]"));
  expectCleanFailure(r, 2, out(), {"type.yaml:", "dynamics.time_step", "expected a number"});
}

TEST_F(BadConfig, WrongTypeMapForBodies) {
  const auto r = runText("type.yaml", "environment: env1\nbodies: {name: a}\n");
  expectCleanFailure(r, 2, out(), {"type.yaml:2:", "bodies", "expected"});
}

TEST_F(BadConfig, ContradictionBothPosesAndPlacement) {
  const auto r =
      runText("both.yaml",
              env3With("^    placement:$", "    poses: [{position: [0, 0, 0]}]\n    placement:"));
  expectCleanFailure(r, 2, out(), {"both.yaml:", "exactly one", "both"});
}

TEST_F(BadConfig, ResolutionZeroOnTheCommandLine) {
  const auto r = run(kConfigDir + "env3.yaml", {"--resolutions", "0"});
  expectCleanFailure(r, 2, out(), {"resolution 0", "expected"});
}

TEST_F(BadConfig, ResolutionNegativeOnTheCommandLine) {
  const auto r = run(kConfigDir + "env3.yaml", {"--resolutions=-64"});
  expectCleanFailure(r, 2, out(), {"-64", "expected"});
}

TEST_F(BadConfig, ResolutionHundredThousandOnTheCommandLine) {
  const auto r = run(kConfigDir + "env3.yaml", {"--resolutions", "100000"});
  expectCleanFailure(r, 2, out(), {"100000", "16384"});
}

TEST_F(BadConfig, ResolutionZeroInTheConfig) {
  const auto r = runText("res.yaml", env3With("^  resolutions: .*$", "  resolutions: [0]"));
  expectCleanFailure(r, 2, out(), {"res.yaml:", "sweep.resolutions", "[1, 16384]"});
}

TEST_F(BadConfig, ResolutionHundredThousandInTheConfig) {
  const auto r = runText("res.yaml", env3With("^  resolutions: .*$", "  resolutions: [100000]"));
  expectCleanFailure(r, 2, out(), {"res.yaml:", "sweep.resolutions", "100000"});
}

TEST_F(BadConfig, ResolutionNotAnInteger) {
  const auto r = run(kConfigDir + "env3.yaml", {"--resolutions", "800px"});
  expectCleanFailure(r, 2, out(), {"800px", "expected"});
}

// Within the config's limit but above what this GL can render at: refused before any frame.
TEST_F(BadConfig, ResolutionAboveTheGlMaximum) {
  int glMax = 0;
  {
    HeadlessGlContext gl(GlPlatform::Auto);
    GlOcclusionQueryBackend backend(gl);
    glMax = backend.maxResolution();
  }
  ASSERT_GT(glMax, 0);
  if (glMax >= limits::kResolution.max)
    GTEST_SKIP() << "this GL renders up to " << glMax << ": the config limit is the tighter one";
  const std::string tooBig = std::to_string(glMax + 1);
  const auto r = run(kConfigDir + "env3.yaml",
                     {"--objects", "3", "--resolutions", tooBig, "--visibility", "gl-queries"});
  expectCleanFailure(r, 2, out(), {tooBig, std::to_string(glMax)});
}

TEST_F(BadConfig, ObjectCountZeroOnTheCommandLine) {
  const auto r = run(kConfigDir + "env3.yaml", {"--objects", "0"});
  expectCleanFailure(r, 2, out(), {"object count 0", "expected"});
}

TEST_F(BadConfig, ObjectCountZeroInTheConfig) {
  const auto r = runText("count.yaml", env3With("^    count: 200.*$", "    count: 0"));
  expectCleanFailure(r, 2, out(), {"count.yaml:", "bodies[0].count", "[1, 100000]"});
}

TEST_F(BadConfig, ObjectCountBeyondAnInteger) {
  const auto r = run(kConfigDir + "env3.yaml", {"--objects", "99999999999"});
  expectCleanFailure(r, 2, out(), {"99999999999", "expected"});
}

TEST_F(BadConfig, ObjectCountAboveTheLimit) {
  const auto r = run(kConfigDir + "env3.yaml", {"--objects", "100001"});
  expectCleanFailure(r, 2, out(), {"100001", "100000"});
}

// Within the count limit, but the placement region cannot hold them: refused as input before a
// single body is placed, not after trying.
TEST_F(BadConfig, ObjectCountTheRegionCannotHoldOnTheCommandLine) {
  const auto r = run(kConfigDir + "env3.yaml", {"--objects", "100000"});
  expectCleanFailure(r, 2, out(), {"100000", "tori", "30%"});
}

TEST_F(BadConfig, ObjectCountTheRegionCannotHoldInTheConfig) {
  const auto r = runText("many.yaml", env3With("^    count: 200.*$", "    count: 100000"));
  expectCleanFailure(r, 2, out(), {"many.yaml:", "placement", "30%"});
}

TEST_F(BadConfig, FramesZero) {
  const auto r = runCdbench(
      {"run", kConfigDir + "env3.yaml", "--frames", "0", "--quiet", "--out", out().string()});
  expectCleanFailure(r, 2, out(), {"--frames", "expected"});
}

TEST_F(BadConfig, UnknownOption) {
  const auto r = run(kConfigDir + "env3.yaml", {"--resolution", "800"});
  expectCleanFailure(r, 2, out(), {"--resolution"});
}

TEST_F(BadConfig, GlPlatformUnknown) {
  const auto r = run(kConfigDir + "env3.yaml", {"--objects", "3", "--gl", "vulkan"});
  expectCleanFailure(r, 2, out(), {"vulkan", "auto, device or surfaceless"});
}

}  // namespace
}  // namespace cdb::test
