// cull/<env>/<strategy>/<backend>/res:<r>: a strategy's cull() of the environment's measured
// frame on a visibility backend, what `cdbench run` reports as cull_ms: each iteration is one
// detect() of the registry's detector (what the runner times), and the iteration's time is its
// culling part, without the exact phase (exact/... and the exact_ms counter). For the CPU peers,
// detectors by themselves that use no backend (backend "-"), it is their whole collision
// detection and the resolution changes nothing.
//
// Set-up per run of the benchmark function, untimed: the backend, its warm-up at the resolution
// (shader variants, framebuffer), the detector's attach (hierarchies) and one detection of the
// frame: strategies keep state from frame to frame (ours keeps its sorted lists) and the first cull
// allocates. The timed iterations then cull the same frame again, as a strategy meeting a frame
// like the previous one does.
#include <cstdint>
#include <string>

#include "bench/BenchmarkSuite.h"
#include "culling/exact/ExactPhase.h"
#include "culling/visibility/VisibilityBackendRegistry.h"
#include "harness/BackendWarmUp.h"

namespace cdb::bench {

namespace {

void cullMeasuredFrame(benchmark::State& state, RecordedFrames& frames,
                       const std::string& environment, const std::string& strategyName,
                       const std::string& backendName, int resolution) {
  const RecordedScene& recorded = frames.recorded(environment);
  const auto poses = frames.poses(environment);
  const int frame = frames.measured(environment).frame;
  const auto backend = warmedUpBackend(frames.resources(), backendName, recorded.config.culling,
                                       recorded.scene, poses, resolution);
  ExactPhase exact(recorded.scene);
  auto detector = DetectorRegistry::builtin().createDetector(
      strategyName, DetectorOptions{resolution, recorded.config.culling}, *backend, exact);
  detector->attach(recorded.scene);
  (void)detector->detect({poses, frame});

  CullingCounters total;
  double exactMs = 0;
  std::uint64_t collidingPairs = 0;
  for (auto _ : state) {
    const DetectedFrame detected = detector->detect({poses, frame});
    state.SetIterationTime(detected.cullMs / 1e3);
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
  state.counters["sets"] = perIteration(double(total.sets));
  state.counters["pcs_objects"] = perIteration(double(total.pcsSize));
  state.counters["pcs_triangles"] = perIteration(double(total.pcsTriangles));
  state.counters["exact_ms"] = perIteration(exactMs);
  state.counters["colliding_pairs"] = perIteration(double(collidingPairs));
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
          registerMilliseconds(cellName("cull", m.environment, strategy, backend, resolution),
                               [&frames, environment = m.environment, strategy, runsOn,
                                resolution](benchmark::State& state) {
                                 cullMeasuredFrame(state, frames, environment, strategy, runsOn,
                                                   resolution);
                               })
              ->UseManualTime();
        }
    }
}

}  // namespace cdb::bench
