// cull/<env>/<strategy>/res:<r>: a strategy's cull() of the environment's measured frame, what
// `cdbench run` reports as cull_ms: the culling alone, without the exact phase (exact/...), on the
// GL occlusion-query backend. For the CPU peers, which decide the colliding pairs themselves,
// cull() is their whole collision detection and the resolution changes nothing.
//
// Set-up per run of the benchmark function, untimed: the backend, its warm-up at the resolution
// (shader variants, framebuffer), the strategy's attach (hierarchies) and one cull of the frame:
// strategies keep state from frame to frame (ours keeps its sorted lists) and the first cull
// allocates. The timed iterations then cull the same frame again, as a strategy meeting a frame
// like the previous one does.
#include <cstdint>
#include <string>

#include "bench/BenchmarkSuite.h"
#include "culling/visibility/GlOcclusionQueryBackend.h"
#include "harness/BackendWarmUp.h"

namespace cdb::bench {

namespace {

void cullMeasuredFrame(benchmark::State& state, RecordedFrames& frames,
                       const std::string& environment, const std::string& strategyName,
                       int resolution) {
  const RecordedScene& recorded = frames.recorded(environment);
  const FrameInput input{frames.poses(environment), frames.measured(environment).frame};
  GlOcclusionQueryBackend backend(frames.gl(), visibilityOptions(recorded.config));
  backend.attachScene(recorded.scene);
  warmUpBackend(backend, recorded.scene, input.poses, resolution);
  auto strategy = StrategyRegistry::builtin().create(strategyName,
                                                     strategyOptions(recorded.config, resolution));
  strategy->attach(recorded.scene, backend);
  (void)strategy->cull(input);

  CullingCounters total;
  std::uint64_t decidedPairs = 0;
  bool decided = false;
  for (auto _ : state) {
    const CullingResult result = strategy->cull(input);
    total.visibility += result.counters.visibility;
    total.sets += result.counters.sets;
    total.pcsSize += result.counters.pcsSize;
    total.pcsTriangles += result.counters.pcsTriangles;
    if (result.decided) {
      decided = true;
      decidedPairs += result.decided->collidingPairs.size();
    }
  }
  state.counters["queries"] = perIteration(double(total.visibility.queries));
  state.counters["draws"] = perIteration(double(total.visibility.draws));
  state.counters["triangles"] = perIteration(double(total.visibility.trianglesDrawn));
  state.counters["sets"] = perIteration(double(total.sets));
  state.counters["pcs_objects"] = perIteration(double(total.pcsSize));
  state.counters["pcs_triangles"] = perIteration(double(total.pcsTriangles));
  // The CPU peers' answer, to set beside exact/<env>/...'s colliding_pairs.
  if (decided) state.counters["colliding_pairs"] = perIteration(double(decidedPairs));
}

}  // namespace

void registerCullBenchmarks(RecordedFrames& frames) {
  for (const MeasuredFrame& m : frames.frames())
    for (const std::string& strategy : StrategyRegistry::builtin().names())
      for (int resolution : kResolutions) {
        const std::string name =
            "cull/" + m.environment + "/" + strategy + "/res:" + std::to_string(resolution);
        benchmark::RegisterBenchmark(
            name.c_str(),
            [&frames, environment = m.environment, strategy, resolution](benchmark::State& state) {
              skipOnError(state, [&] {
                cullMeasuredFrame(state, frames, environment, strategy, resolution);
              });
            })
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime();
      }
}

}  // namespace cdb::bench
