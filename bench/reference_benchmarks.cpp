// Two costs outside every culling time, on the three environments:
//  truth/<env>: the ground truth (GroundTruth::compute, every pair of objects tested exactly) on
//               the environment's measured frame: the reference every strategy is checked against.
//  dynamics/<env>: one frame of the environment's rigid-body simulation (ODE, the config's steps
//               per frame) from the config's start, warm-up frames included, with the config's
//               seed and body counts (--objects aside): what producing the poses costs. After
//               the config's frame count the simulation starts again, untimed.
// Set-up, untimed: the ground truth's per-mesh trees; the simulation's bodies.
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "bench/BenchmarkSuite.h"
#include "culling/exact/GroundTruth.h"
#include "scenes/RigidBodySimulation.h"

namespace cdb::bench {

void registerReferenceBenchmarks(RecordedFrames& frames) {
  for (const MeasuredFrame& m : frames.frames()) {
    benchmark::RegisterBenchmark(("truth/" + m.environment).c_str(), [&frames,
                                                                      environment = m.environment](
                                                                         benchmark::State& state) {
      skipOnError(state, [&] {
        const GroundTruth truth(frames.recorded(environment).scene);
        const std::span<const Pose> poses = frames.poses(environment);
        std::uint64_t collidingPairs = 0;
        for (auto _ : state) collidingPairs += truth.compute(poses).collidingPairs.size();
        state.counters["colliding_pairs"] = perIteration(double(collidingPairs));
      });
    })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("dynamics/" + m.environment).c_str(), [&frames,
                                                                         environment = m.environment](
                                                                            benchmark::State& state) {
      skipOnError(state, [&] {
        const RecordedScene& unsimulated = frames.unsimulated(environment);
        const ScenarioConfig& config = unsimulated.config;
        const int frameCount = config.dynamics.warmupFrames + config.dynamics.frames;
        auto simulation =
            std::make_unique<RigidBodySimulation>(config, unsimulated.scene, config.seed);
        int frame = 0;
        for (auto _ : state) {
          if (frame == frameCount) {
            state.PauseTiming();
            simulation.reset();
            simulation = std::make_unique<RigidBodySimulation>(config, unsimulated.scene, config.seed);
            frame = 0;
            state.ResumeTiming();
          }
          simulation->stepFrame();
          ++frame;
        }
        state.counters["bodies"] = double(unsimulated.scene.objectCount());
        state.counters["steps_per_frame"] = double(config.dynamics.stepsPerFrame);
      });
    })->Unit(benchmark::kMillisecond);
  }
}

}  // namespace cdb::bench
