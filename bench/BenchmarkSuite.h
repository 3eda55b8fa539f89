#pragma once
// The micro-benchmarks of cdbench_bench and what they share. Names (Google Benchmark's
// --benchmark_filter takes a regular expression over them):
//
//   cull/<env>/<strategy>/<backend>/res:<r>/manual_time   a strategy's cull() of the frame on a
//                                             visibility backend (backend "-" for the CPU peers)
//   cpu_tiles/<env>/<strategy>/<evaluation>/threads:<n>/manual_time   the cpu backend's tile sizes,
//                                             plain evaluation and threads (800 px)
//   floor/<env>/<strategy>/<backend>/res:<r>/real_time   that cull's backend work replayed bare
//   exact/<env>/ours_sets                     the exact phase on the sets `ours` leaves (800)
//   exact/<env>/all_pairs_sets                   the exact phase on one set of every object
//   bvh_build/<mesh>/<env>                    one OBB tree build under the env's tree options
//   truth/<env>                               the ground truth on the frame
//   dynamics/<env>                            one frame of the env's rigid-body simulation
//
// for env1, env2, env3 (RecordedFrames.h says which frame), every visibility backend that starts
// here (`cdbench backends`) and r = 256, 800; each file's head says what its benchmarks measure.
// Times are milliseconds per iteration; counters are per iteration. The GL benchmarks are timed on
// the wall clock (Google Benchmark then appends /real_time to their names): GL work runs
// asynchronously, on llvmpipe in its own threads, so the calling thread's CPU time misses most of
// it. Google Benchmark's default --benchmark_min_time (0.5 s) keeps a heavy cell to one iteration:
// a cull of env2 by CULLIDE on a GL backend takes 30-55 s on llvmpipe (RecordedFrames.h).
#include <exception>
#include <string>
#include <string_view>
#include <utility>

#include <benchmark/benchmark.h>

#include "bench/RecordedFrames.h"
#include "culling/DetectorRegistry.h"
#include "culling/visibility/VisibilityBackend.h"

namespace cdb::bench {

inline constexpr int kResolutions[] = {256, 800};


// Runs `body`, turning an exception (a missing dragon, no GL) into a skipped benchmark that
// carries its message, so that one unavailable environment does not stop the suite.
template <class Body>
void skipOnError(benchmark::State& state, Body&& body) {
  try {
    body();
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
  }
}

// Registers the benchmark `name`, reported in milliseconds, whose body runs under skipOnError.
template <class Body>
auto* registerMilliseconds(const std::string& name, Body body) {
  return benchmark::RegisterBenchmark(name.c_str(), [body = std::move(body)](benchmark::State& state) {
           skipOnError(state, [&] { body(state); });
         })->Unit(benchmark::kMillisecond);
}

// The name of a strategy's cell: `<kind>/<env>/<strategy>/<backend>/res:<r>`.
[[nodiscard]] inline std::string cellName(std::string_view kind, const std::string& environment,
                                          const std::string& strategy, const std::string& backend,
                                          int resolution) {
  return std::string(kind) + "/" + environment + "/" + strategy + "/" + backend +
         "/res:" + std::to_string(resolution);
}

// Per-iteration counters: the sum over the iterations, divided by their number when reported.
[[nodiscard]] inline benchmark::Counter perIteration(double total) {
  return benchmark::Counter(total, benchmark::Counter::kAvgIterations);
}

void registerCullBenchmarks(RecordedFrames& frames);
void registerFloorBenchmarks(RecordedFrames& frames);
void registerExactPhaseBenchmarks(RecordedFrames& frames);
void registerBvhBuildBenchmarks(RecordedFrames& frames);
void registerReferenceBenchmarks(RecordedFrames& frames);

}  // namespace cdb::bench
