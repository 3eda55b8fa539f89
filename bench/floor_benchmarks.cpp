// floor/<env>/<strategy>/res:<r>: the backend's floor under an image-based strategy. The GL work
// of one cull of the measured frame (its passes, draws, queries and fetches, recorded through a
// RecordingBackend after one unrecorded cull, as cull/... times it) is replayed as bare GL commands
// (GlDrawFloor) with no algorithm around them: no strategy can cull that frame with that work
// faster on this backend. cull/... divided by floor/... of the same cell is the strategy's own
// overhead; compareWithFloor (cdbench_floor) makes the same comparison in one process.
//
// Set-up per run of the benchmark function, untimed: the recording (two culls), lowering it to
// draw commands, and one replay, which compiles the floor's shader variants and checks that the
// replay answers every query as the strategy's run did (the benchmark is skipped otherwise). A
// recording of CULLIDE on env2 holds ~6 million operations, about 2 GB.
#include <string>

#include "bench/BenchmarkSuite.h"
#include "culling/visibility/GlDrawFloor.h"
#include "culling/visibility/GlOcclusionQueryBackend.h"
#include "culling/visibility/RecordingBackend.h"
#include "harness/BackendWarmUp.h"
#include "harness/FloorComparison.h"

namespace cdb::bench {

namespace {

void replayRecordedCull(benchmark::State& state, RecordedFrames& frames,
                        const std::string& environment, const std::string& strategy,
                        int resolution) {
  const RecordedScene& recorded = frames.recorded(environment);
  const int frame = frames.measured(environment).frame;
  const VisibilityOptions options = visibilityOptions(recorded.config);
  GlOcclusionQueryBackend backend(frames.gl(), options);
  backend.attachScene(recorded.scene);
  warmUpBackend(backend, recorded.scene, frames.poses(environment), resolution);
  RecordingBackend recorder(backend);
  const VisibilityCounters work = recordCullWork(recorder, recorded, strategy, resolution, frame);

  GlDrawFloor floor(frames.gl(), options);
  GlDrawFloor::Prepared prepared = floor.prepare(recorder.ops());
  floor.replayOnce(prepared);
  if (!prepared.answersMatch()) {
    state.SkipWithError("the bare replay answered some query differently from the strategy's run");
    return;
  }
  for (auto _ : state) floor.replayOnce(prepared);
  state.counters["queries"] = double(prepared.queries());
  state.counters["draws"] = double(prepared.draws());
  state.counters["triangles"] = double(work.trianglesDrawn);
  state.counters["passes"] = double(prepared.passes());
  state.counters["fetches"] = double(prepared.fetches());
}

}  // namespace

void registerFloorBenchmarks(RecordedFrames& frames) {
  for (const MeasuredFrame& m : frames.frames())
    for (const std::string& strategy : StrategyRegistry::builtin().names()) {
      if (isCpuPeer(strategy)) continue;
      for (int resolution : kResolutions) {
        const std::string name =
            "floor/" + m.environment + "/" + strategy + "/res:" + std::to_string(resolution);
        benchmark::RegisterBenchmark(
            name.c_str(),
            [&frames, environment = m.environment, strategy, resolution](benchmark::State& state) {
              skipOnError(state, [&] {
                replayRecordedCull(state, frames, environment, strategy, resolution);
              });
            })
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime();
      }
    }
}

}  // namespace cdb::bench
