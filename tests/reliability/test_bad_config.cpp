// Bad configs and bad command-line values through the real binary: exit 2, one line naming the
// file or option, the key and what was expected, and no result file. One case per way out of the
// program; what each kind of bad YAML says is tested on the loader itself (tests/scenes/
// test_config.cpp), which the binary calls and whose message it prints as is.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

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

// The YAML parser's error and the schema's error leave through the loader's InputError.
TEST_F(BadConfig, MalformedYaml) {
  const auto r = runText("malformed.yaml", "environment: env1\nbodies: [\n  {name: a\n");
  expectCleanFailure(r, 2, out(), {"malformed.yaml:", "expected valid YAML"});
}

TEST_F(BadConfig, UnknownTopLevelKey) {
  const auto r = runText("unknown.yaml", env3With("^seed: 1.*$", "seed: 1\nsede: 2"));
  expectCleanFailure(r, 2, out(), {"unknown.yaml:14:", "sede", "expected a known key"});
}

// No --strategies: the config's own list is what is wrong, so the message names the config.
TEST_F(BadConfig, UnknownStrategyInTheConfig) {
  const auto config =
      dir.write("strategy.yaml", env3With("^  strategies: .*$", "  strategies: [cullide, nosuch]"));
  const auto r = runCdbench({"run", config.string(), "--quiet", "--out", out().string()});
  expectCleanFailure(r, 2, out(), {"strategy.yaml", "nosuch", "cullide"});
}

// The config asks for raw mode and lists only what draws nothing: the message names the config
// and the key, and says how to run the image-based strategies.
TEST_F(BadConfig, RawModeInTheConfigWithOnlyACpuPeer) {
  std::string text = env3With("^  strategies: .*$", "  strategies: [bullet, all_pairs]");
  const std::regex mode("conservative: true");
  ASSERT_TRUE(std::regex_search(text, mode));
  text = std::regex_replace(text, mode, "conservative: false");
  const auto config = dir.write("raw.yaml", text);
  const auto r = runCdbench({"run", config.string(), "--frames", "2", "--quiet", "--out", out().string()});
  expectCleanFailure(r, 2, out(),
                     {"raw.yaml", "culling.visibility.conservative: false", "draws anything",
                      "name the image-based strategies with --strategies"});
}

// --raw on a config that lists reference rows beside image-based strategies (as the shipped ones
// do): the reference rows are left out with a note, the rest runs raw.
TEST_F(BadConfig, RawModeLeavesOutTheConfigsReferenceRows) {
  const auto config =
      dir.write("raw.yaml", env3With("^  strategies: .*$", "  strategies: [cullide, bullet]"));
  const auto r = runCdbench({"run", config.string(), "--raw", "--frames", "2", "--frame-stride",
                             "2", "--objects", "50", "--resolutions", "64", "--repeats", "1",
                             "--no-truth", "--out", out().string()});
  ASSERT_EQ(r.exitCode, 0) << r.stdErr;
  EXPECT_NE(r.stdErr.find("run: raw mode: bullet is a CPU peer and draws nothing"),
            std::string::npos)
      << r.stdErr;
  std::ifstream frames(out() / "frames.csv");
  std::string header, row;
  std::getline(frames, header);
  int rows = 0;
  while (std::getline(frames, row)) {
    EXPECT_EQ(row.find("bullet"), std::string::npos) << row;
    rows += row.find("cullide") != std::string::npos;
  }
  EXPECT_GT(rows, 0);
}

// A strategy of order-independent passes on a backend without them (gl-queries): left out of the
// config's list with a note, refused when named with --strategies.
TEST_F(BadConfig, OrderIndependentStrategyOnABackendWithoutIt) {
  const auto config =
      dir.write("oi.yaml", env3With("^  strategies: .*$", "  strategies: [cullide, cullide_oi]"));
  const std::vector<std::string> small = {"--visibility", "gl-queries", "--frames", "2",
                                          "--frame-stride", "2", "--objects", "50",
                                          "--resolutions", "64", "--repeats", "1", "--no-truth"};
  std::vector<std::string> args = {"run", config.string(), "--out", out().string()};
  args.insert(args.end(), small.begin(), small.end());
  const auto r = runCdbench(args);
  ASSERT_EQ(r.exitCode, 0) << r.stdErr;
  EXPECT_NE(r.stdErr.find("run: cullide_oi needs order-independent passes, which the gl-queries "
                          "backend does not offer: left out"),
            std::string::npos)
      << r.stdErr;

  const auto named = dir.path() / "named";
  args = {"run", config.string(), "--strategies", "cullide_oi", "--out", named.string()};
  args.insert(args.end(), small.begin(), small.end());
  expectCleanFailure(runCdbench(args), 2, named,
                     {"--strategies: cullide_oi needs order-independent passes", "gl-queries"});
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

// A value the loader accepts but the run cannot use (a mesh on no asset path) is found before the
// output folder is claimed: the failed run leaves no run.json, and the corrected config runs into
// the same --out.
TEST_F(BadConfig, TheCorrectedConfigRunsIntoTheSameFolder) {
  const std::string torus = R"(mesh: \{kind: torus[^}]*\})";
  const auto bad = dir.write("env3.yaml", env3With(torus, "mesh: {kind: asset, asset: nosuchmesh, asset_size: 0.8}"));
  const std::initializer_list<std::string> small = {"--objects", "3", "--resolutions", "64"};
  expectCleanFailure(run(bad.string(), small), 2, out(), {"nosuchmesh", "not found"});
  EXPECT_FALSE(std::filesystem::exists(out() / "run.json"));
  dir.write("env3.yaml", shippedConfig("env3.yaml"));
  const auto r = run(bad.string(), small);
  ASSERT_EQ(r.exitCode, 0) << r.stdErr;
  for (const char* f : kResultFiles) EXPECT_TRUE(std::filesystem::exists(out() / f)) << f;
}

// Bad values on the command line, each with env3: the option parser's own refusals (an unknown
// option, text where an integer goes) and the checks of the values it accepted (ranges, names,
// a count the placement region cannot hold).
struct BadArguments {
  const char* name;
  std::vector<std::string> arguments;
  std::vector<std::string> mentions;
};

const BadArguments kBadArguments[] = {
    {"UnknownStrategy", {"--strategies", "cullide,nosuch"}, {"nosuch", "expected one of", "cullide"}},
    {"ResolutionZero", {"--resolutions", "0"}, {"resolution 0", "expected"}},
    {"ResolutionNegative", {"--resolutions=-64"}, {"-64", "expected"}},
    {"ResolutionHundredThousand", {"--resolutions", "100000"}, {"100000", "16384"}},
    {"ResolutionNotAnInteger", {"--resolutions", "800px"}, {"800px", "expected"}},
    {"ObjectCountZero", {"--objects", "0"}, {"object count 0", "expected"}},
    {"ObjectCountBeyondAnInteger", {"--objects", "99999999999"}, {"99999999999", "expected"}},
    {"ObjectCountAboveTheLimit", {"--objects", "100001"}, {"100001", "100000"}},
    // Within the count limit, but the placement region cannot hold them: refused as input before
    // a single body is placed, not after trying.
    {"ObjectCountTheRegionCannotHold", {"--objects", "100000"}, {"100000", "tori", "30%"}},
    {"FramesZero", {"--frames", "0"}, {"--frames", "expected"}},
    {"UnknownOption", {"--resolution", "800"}, {"--resolution"}},
    {"GlPlatformUnknown", {"--objects", "3", "--gl", "vulkan"}, {"vulkan", "auto, device or surfaceless"}},
    // Raw rasterisation applies to what draws: not to a CPU peer or the all_pairs reference.
    {"RawWithACpuPeer", {"--raw", "--strategies", "cullide,fcl"},
     {"--raw", "fcl is a CPU peer", "draws nothing", "leave it out of --strategies"}},
    {"RawWithTheReference", {"--raw", "--strategies", "all_pairs"}, {"--raw", "all_pairs", "draws nothing"}},
    {"RawOffsetWithoutRaw", {"--raw-offset", "0.001"}, {"--raw-offset", "give --raw"}},
    {"RawOffsetNegative", {"--raw", "--raw-offset=-0.5"}, {"--raw-offset -0.5", "expected 0..1"}},
    {"RawOffsetAboveOne", {"--raw", "--raw-offset", "2"}, {"--raw-offset 2", "expected 0..1"}},
    {"RawOffsetNotANumber", {"--raw", "--raw-offset", "tiny"}, {"--raw-offset", "tiny"}},
};

class BadCommandLine : public ::testing::TestWithParam<BadArguments> {};

TEST_P(BadCommandLine, ExitsTwoWithOneLine) {
  const ScratchDir dir;
  const auto out = dir.path() / "out";
  const std::vector<std::string>& bad = GetParam().arguments;
  // smallRun gives --frames itself, and an option is given once.
  std::vector<std::string> args = {"run", kEnv3, "--quiet", "--out", out.string()};
  if (bad.front() == "--frames")
    args.insert(args.end(), bad.begin(), bad.end());
  else
    args = smallRun(kEnv3, out, bad);
  expectCleanFailure(runCdbench(args), 2, out, GetParam().mentions);
}

INSTANTIATE_TEST_SUITE_P(Env3, BadCommandLine, ::testing::ValuesIn(kBadArguments),
                         [](const auto& param) { return std::string(param.param.name); });

}  // namespace
}  // namespace cdb::test
