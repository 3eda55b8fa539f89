// floor/<env>/<strategy>/<backend>/res:<r>: a visibility backend's floor under an image-based
// strategy. The backend work of one cull of the measured frame (its passes, draws, queries and
// fetches, recorded through a RecordingBackend after one unrecorded cull, as cull/... times it)
// is issued again with no algorithm around it, on the backend's own floor (BackendFloor: bare GL
// commands for gl-queries, the recorded calls replayed for the others): no strategy can cull that
// frame with that work faster on this backend. cull/... divided by floor/... of the same cell is
// the strategy's own overhead; compareWithFloor (cdbench_floor) makes the same comparison in one
// process.
//
// Set-up per run of the benchmark function, untimed (FloorSetup): the recording (two culls),
// preparing it, and one replay, which compiles shader variants and checks that the replay answers
// every query as the strategy's run did (the benchmark is skipped otherwise). A recording of
// CULLIDE on env2 holds ~6 million operations, about 2 GB.
#include <string>

#include "bench/BenchmarkSuite.h"
#include "harness/measure/FloorComparison.h"

namespace cdb::bench {

namespace {

void replayRecordedCull(benchmark::State& state, RecordedFrames& frames,
                        const std::string& environment, const std::string& strategy,
                        const std::string& backend, int resolution) {
  FloorSetup setup(frames.resources(), backend, frames.recorded(environment), strategy, resolution,
                   frames.measured(environment).frame);
  if (!setup.answersMatch()) {
    state.SkipWithError("the bare replay answered some query differently from the strategy's run");
    return;
  }
  for (auto _ : state) setup.floor().replayOnce();
  const VisibilityCounters& work = setup.work();
  state.counters["queries"] = double(work.queries);
  state.counters["draws"] = double(work.draws);
  state.counters["triangles"] = double(work.trianglesDrawn);
  state.counters["passes"] = double(work.passes);
  state.counters["fetches"] = double(work.fetches);
}

}  // namespace

void registerFloorBenchmarks(RecordedFrames& frames) {
  for (const MeasuredFrame& m : frames.frames())
    for (const std::string& strategy : DetectorRegistry::builtin().names()) {
      if (!DetectorRegistry::builtin().usesBackend(strategy)) continue;
      for (const std::string& backend : frames.backends())
        for (int resolution : kResolutions)
          if (DetectorRegistry::builtin().runsOn(strategy, backend))
            registerMilliseconds(cellName("floor", m.environment, strategy, backend, resolution),
                               [&frames, environment = m.environment, strategy, backend,
                                resolution](benchmark::State& state) {
                                 replayRecordedCull(state, frames, environment, strategy, backend,
                                                    resolution);
                               })
              ->UseRealTime();
    }
}

}  // namespace cdb::bench
