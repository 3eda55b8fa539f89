// cdbench_bench: Google Benchmark micro-benchmarks of the culling strategies, their backend floors,
// the exact phase and the BVH build on recorded frames of env1, env2 and env3 (the list and what
// each measures: bench/BenchmarkSuite.h; the frames: bench/RecordedFrames.h). Google Benchmark's
// flags work as usual; --benchmark_out=FILE --benchmark_out_format=json writes what its
// tools/compare.py reads. scripts/bench.sh builds and runs it. The whole suite takes 20-30 minutes
// on 2 cores with llvmpipe, two thirds of it CULLIDE, cullide_bvh and sorted on env2.
#include <charconv>
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <benchmark/benchmark.h>

#include "bench/BenchmarkSuite.h"
#include "core/Errors.h"
#include "harness/common/MachineInfo.h"
#include "scenes/ConfigLoader.h"
#include "scenes/SceneBuilder.h"

namespace {

constexpr const char* kOwnFlags =
    "\ncdbench_bench's own flags:\n"
    "  --objects ENV=N   count of ENV's swept group (env3 only; default 200)\n"
    "  --frame ENV=K     the frame of ENV measured (defaults: env1=150 env2=200 env3=147)\n"
    "  --configs DIR     folder of env1.yaml .. env3.yaml (default: the source tree's configs/)\n"
    "  --assets DIR      asset folder with the dragon, searched before $CDBENCH_ASSETS\n"
    "  --gl PLATFORM     auto, device or surfaceless (EGL)\n";

void printHelp() {
  benchmark::PrintDefaultHelp();
  std::fputs(kOwnFlags, stdout);
}

// "env3=20": `set` applied to env3's measured frame and 20.
template <class Set>
void applyOverride(std::vector<cdb::bench::MeasuredFrame>& frames, const std::string& flag,
                   const std::string& text, Set set) {
  const auto eq = text.find('=');
  int value = -1;
  if (eq != std::string::npos) {
    const char* last = text.data() + text.size();
    const auto [end, error] = std::from_chars(text.data() + eq + 1, last, value);
    if (error != std::errc() || end != last) value = -1;
  }
  if (value < 0) throw cdb::InputError(flag + " " + text + ": expected ENV=N with N >= 0");
  const std::string environment = text.substr(0, eq);
  for (auto& f : frames)
    if (f.environment == environment) return set(f, value);
  throw cdb::InputError(flag + " " + text + ": unknown environment '" + environment + "'");
}

// What the JSON context records of a measured frame: "frame 147 of .../env3.yaml, 200 objects".
std::string describe(const cdb::bench::RecordedFrames& frames, const cdb::bench::MeasuredFrame& m) {
  cdb::ScenarioConfig config = cdb::loadScenarioConfig(frames.configPath(m.environment));
  if (m.objects > 0) config = cdb::withObjectCount(config, m.objects);
  int objects = 0;
  for (const auto& group : config.bodies) objects += group.count;
  return "frame " + std::to_string(m.frame) + " of " + frames.configPath(m.environment).string() +
         ", " + std::to_string(objects) + " objects";
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv, printHelp);
  CLI::App app{"cdbench micro-benchmarks (Google Benchmark)"};
  std::vector<std::string> objects, frameFlags, assets;
  std::string configs = std::string(CDBENCH_SOURCE_DIR) + "/configs", glPlatform = "auto";
  app.add_option("--objects", objects);
  app.add_option("--frame", frameFlags);
  app.add_option("--configs", configs);
  app.add_option("--assets", assets);
  app.add_option("--gl", glPlatform);
  app.set_help_flag();  // Google Benchmark's Initialize already answered --help
  try {
    app.parse(argc, argv);
    using namespace cdb;
    std::vector<bench::MeasuredFrame> measured = bench::defaultMeasuredFrames();
    for (const auto& o : objects)
      applyOverride(measured, "--objects", o, [](auto& f, int n) { f.objects = n; });
    for (const auto& f : frameFlags)
      applyOverride(measured, "--frame", f, [](auto& m, int k) { m.frame = k; });
    bench::RecordedFrames frames(configs, assets, parseGlPlatform(glPlatform), measured);

    benchmark::AddCustomContext("cdbench_backends", frames.backendDescription());
    benchmark::AddCustomContext("cdbench_commit", probeMachine().gitCommit);
    for (const auto& m : frames.frames())
      benchmark::AddCustomContext("cdbench_" + m.environment, describe(frames, m));

    bench::registerBvhBuildBenchmarks(frames);
    bench::registerExactPhaseBenchmarks(frames);
    bench::registerReferenceBenchmarks(frames);
    bench::registerCullBenchmarks(frames);
    bench::registerFloorBenchmarks(frames);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "cdbench_bench: error: %s\n%s", e.what(), kOwnFlags);
    return 2;
  } catch (const cdb::InputError& e) {
    std::fprintf(stderr, "cdbench_bench: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cdbench_bench: failed: %s\n", e.what());
    return 1;
  }
}
