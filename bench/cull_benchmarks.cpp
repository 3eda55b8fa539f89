// cull/<env>/<strategy>/<backend>/res:<r>: a strategy's cull() of the environment's measured
// frame on a visibility backend, what `cdbench run` reports as cull_ms: each iteration is one
// detect() of the registry's detector (what the runner times), and the iteration's time is its
// culling part, without the exact phase (exact/... and the exact_ms counter). For what uses no
// backend (backend "-": the CPU peers and all_pairs), it is the whole collision detection, the
// exact phase included, and the resolution changes nothing.
//
//
// cpu_tiles/<env>/<strategy>/<evaluation>/threads:<n>/manual_time: the same on the cpu backend at
// 800 px, evaluated on demand in tiles of 16, 32 or 64 pixels (tile:<t>) or plainly (plain: every
// write rasterised, every test tested, one tile), at 1 and 2 threads: what the tile size and the
// threads change, with the tile counters. env3: ours, cullide and cullide_oi, every evaluation;
// env2: cullide, quick_cullide and cullide_oi, plain and tile:64.
//
// gl_profile/env3/<strategy>/<backend>/res:<800|64>[/raw]/manual_time: the same cull on a GL
// backend (conservative at 800 and 64 px, raw at 800) with every draw timed on the GPU
// (VisibilityOptions::timeGpu; the queries add a little to the time), for cullide, cullide_oi and
// ours: where a frame's time goes. Counters per frame: draws, fetches
// (read-backs), fetch_wait_ms (the CPU waiting for answers: the GPU finishing what was issued, then
// the copy), gpu_draw_ms (the GPU's time in the draws) and cpu_ms (the rest: the strategy and the
// issuing of draws, cull time minus the waits); on gl-compute also the GPU time of each stage of
// its chain (gpu_setup_ms, gpu_bin_ms, gpu_sort_ms, gpu_evaluate_ms).
//
// Set-up per run of the benchmark function, untimed: the backend, its warm-up at the resolution
// (shader variants, framebuffer), the detector's attach (hierarchies) and one detection of the
// frame: strategies keep state from frame to frame (ours keeps its sorted lists) and the first cull
// allocates. The timed iterations then cull the same frame again, as a strategy meeting a frame
// like the previous one does.
#include <cstdint>
#include <string>
#include <utility>

#include "bench/BenchmarkSuite.h"
#include "culling/exact/ExactPhase.h"
#include "culling/visibility/VisibilityBackendRegistry.h"
#include "culling/visibility/cpu/CpuRasterBackend.h"
#include "harness/measure/BackendWarmUp.h"

namespace cdb::bench {

namespace {

// How a cpu backend evaluates (cpu_tiles/...), or nothing to change.
struct CpuSetting {
  bool given = false;
  CpuEvaluation evaluation;
  int threads = 1;
};

// A GL backend with its draws timed on the GPU (gl_profile/...), conservative or raw.
struct GlProfiling {
  bool timeGpu = false;
  bool raw = false;
};

void cullMeasuredFrame(benchmark::State& state, RecordedFrames& frames,
                       const std::string& environment, const std::string& strategyName,
                       const std::string& backendName, int resolution, const CpuSetting& cpu = {},
                       const GlProfiling& profiling = {}) {
  const RecordedScene& recorded = frames.recorded(environment);
  const auto poses = frames.poses(environment);
  const int frame = frames.measured(environment).frame;
  const auto backend = warmedUpBackend(frames.resources(), backendName, recorded.config.culling,
                                       recorded.scene, poses, resolution);
  if (cpu.given) {
    auto& rasteriser = dynamic_cast<CpuRasterBackend&>(*backend);
    VisibilityOptions options;
    options.threads = cpu.threads;
    rasteriser.setOptions(options);
    rasteriser.setEvaluation(cpu.evaluation);
  }
  if (profiling.timeGpu) {
    VisibilityOptions options = visibilityOptionsOf(recorded.config.culling);
    options.timeGpu = true;
    if (profiling.raw) options.conservative = false;
    backend->setOptions(options);
  }
  // On the cpu backend's threads, as `cdbench run --threads` runs it.
  ExactPhase exact(recorded.scene, cpu.given ? cpu.threads : 1);
  const bool drawsNothing = !DetectorRegistry::builtin().usesBackend(strategyName);
  auto detector = DetectorRegistry::builtin().createDetector(
      strategyName, DetectorOptions{resolution, recorded.config.culling}, *backend, exact);
  detector->attach(recorded.scene);
  (void)detector->detect({poses, frame});

  CullingCounters total;
  double exactMs = 0, cullMs = 0;
  std::uint64_t collidingPairs = 0;
  for (auto _ : state) {
    const DetectedFrame detected = detector->detect({poses, frame});
    // What draws nothing is timed whole: all_pairs' culling (a sweep) takes microseconds and the
    // exact phase the rest, and a manual time near zero would keep the benchmark iterating.
    state.SetIterationTime((drawsNothing ? detected.cullMs + detected.exactMs : detected.cullMs) /
                           1e3);
    cullMs += detected.cullMs;
    const CullingCounters c = detected.cullingCounters();
    total.visibility += c.visibility;
    total.sets += c.sets;
    total.pcsSize += c.pcsSize;
    total.pcsTriangles += c.pcsTriangles;
    exactMs += detected.exactMs;
    collidingPairs += detected.report.collidingPairs.size();
  }
  state.counters["queries"] = perIteration(double(total.visibility.queries));
  state.counters["draws"] = perIteration(double(total.visibility.draws));
  state.counters["triangles"] = perIteration(double(total.visibility.trianglesDrawn));
  state.counters["pixels_tested"] = perIteration(double(total.visibility.pixelsTested));
  state.counters["pixels_written"] = perIteration(double(total.visibility.pixelsWritten));
  state.counters["tile_tests"] = perIteration(double(total.visibility.tileTests));
  state.counters["tile_tests_by_bounds"] = perIteration(double(total.visibility.tileTestsByBounds));
  state.counters["tile_tests_skipped"] = perIteration(double(total.visibility.tileTestsSkipped));
  state.counters["tile_writes"] = perIteration(double(total.visibility.tileWrites));
  state.counters["tile_writes_drawn"] = perIteration(double(total.visibility.tileWritesRasterised));
  state.counters["sets"] = perIteration(double(total.sets));
  state.counters["pcs_objects"] = perIteration(double(total.pcsSize));
  state.counters["pcs_triangles"] = perIteration(double(total.pcsTriangles));
  state.counters["exact_ms"] = perIteration(exactMs);
  state.counters["colliding_pairs"] = perIteration(double(collidingPairs));
  if (profiling.timeGpu) {
    const double waitMs = double(total.visibility.fetchWaitNs) / 1e6;
    state.counters["fetches"] = perIteration(double(total.visibility.fetches));
    state.counters["fetch_wait_ms"] = perIteration(waitMs);
    state.counters["gpu_draw_ms"] = perIteration(double(total.visibility.gpuDrawNs) / 1e6);
    state.counters["cpu_ms"] = perIteration(cullMs - waitMs);
    if (total.visibility.gpuEvaluateNs > 0) {  // gl-compute's stages
      state.counters["gpu_setup_ms"] = perIteration(double(total.visibility.gpuSetupNs) / 1e6);
      state.counters["gpu_bin_ms"] = perIteration(double(total.visibility.gpuBinNs) / 1e6);
      state.counters["gpu_sort_ms"] = perIteration(double(total.visibility.gpuSortNs) / 1e6);
      state.counters["gpu_evaluate_ms"] = perIteration(double(total.visibility.gpuEvaluateNs) / 1e6);
    }
  }
}

}  // namespace

void registerCullBenchmarks(RecordedFrames& frames) {
  for (const MeasuredFrame& m : frames.frames())
    for (const std::string& strategy : DetectorRegistry::builtin().names()) {
      // A CPU peer or a reference uses no backend: one entry, on the default one (it draws
      // nothing on it).
      const std::vector<std::string> backends =
          !DetectorRegistry::builtin().usesBackend(strategy) ? std::vector<std::string>{"-"} : frames.backends();
      for (const std::string& backend : backends)
        for (int resolution : kResolutions) {
          const std::string runsOn =
              backend == "-" ? std::string(VisibilityBackendRegistry::kDefault) : backend;
          if (!DetectorRegistry::builtin().runsOn(strategy, runsOn)) continue;
          registerMilliseconds(cellName("cull", m.environment, strategy, backend, resolution),
                               [&frames, environment = m.environment, strategy, runsOn,
                                resolution](benchmark::State& state) {
                                 cullMeasuredFrame(state, frames, environment, strategy, runsOn,
                                                   resolution);
                               })
              ->UseManualTime();
        }
    }
  // The cpu backend's evaluation: tile sizes, the plain evaluation, threads (env3, 800 px).
  struct Evaluation {
    std::string name;
    CpuEvaluation evaluation;
  };
  const Evaluation evaluations[] = {{"plain", {0, false, false}},
                                    {"tile:16", {16, true, true}},
                                    {"tile:32", {32, true, true}},
                                    {"tile:64", {64, true, true}}};
  const auto registerEvaluation = [&frames](const std::string& environment,
                                            const std::string& strategy, const Evaluation& e) {
    for (int threads : {1, 2}) {
      const CpuSetting cpu{true, e.evaluation, threads};
      registerMilliseconds("cpu_tiles/" + environment + "/" + strategy + "/" + e.name +
                               "/threads:" + std::to_string(threads),
                           [&frames, environment, strategy, cpu](benchmark::State& state) {
                             cullMeasuredFrame(state, frames, environment, strategy, "cpu", 800,
                                               cpu);
                           })
          ->UseManualTime();
    }
  };
  for (const std::string strategy : {"ours", "cullide", "cullide_oi"})
    for (const Evaluation& e : evaluations) registerEvaluation("env3", strategy, e);
  // env2's small triangles: what the demand-driven evaluation saves against drawing every
  // command's triangles (docs/cpu-backend-history.md, "the plain evaluation on env2").
  for (const std::string strategy : {"cullide", "quick_cullide", "cullide_oi"})
    for (const Evaluation& e : evaluations)
      if (e.name == "plain" || e.name == "tile:64") registerEvaluation("env2", strategy, e);
  // Where a GL backend's time goes (env3): at 800 px, conservative and raw (what the conservative
  // stage costs), and at 64 px (what is left when there are hardly any pixels).
  for (const std::string& backend : frames.backends()) {
    if (backend == VisibilityBackendRegistry::kDefault) continue;
    for (const std::string strategy : {"cullide", "cullide_oi", "ours"}) {
      if (!DetectorRegistry::builtin().runsOn(strategy, backend)) continue;
      for (const auto& [resolution, raw] : {std::pair{800, false}, {800, true}, {64, false}})
        registerMilliseconds(
            cellName("gl_profile", "env3", strategy, backend, resolution) + (raw ? "/raw" : ""),
            [&frames, strategy, backend, resolution, raw](benchmark::State& state) {
              cullMeasuredFrame(state, frames, "env3", strategy, backend, resolution, {},
                                GlProfiling{true, raw});
            })
            ->UseManualTime();
    }
  }
}

}  // namespace cdb::bench
