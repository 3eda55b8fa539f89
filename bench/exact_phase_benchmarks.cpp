// exact/<env>/ours_sets and exact/<env>/all_pairs_sets: the exact phase alone (sweep-and-prune
// inside each set, then the triangle-triangle tests), what `cdbench run` reports as exact_ms, on
// the environment's measured frame.
//  ours_sets:   the potentially colliding sets the thesis' approach (`ours`) leaves at 800 x 800
//               (the thesis' resolution for env3), each member restricted to the triangles it
//               kept: the exact work left after culling.
//  all_pairs_sets: the sets of the all_pairs reference (one set holding every object with all its
//               triangles): the exact phase doing the whole job with no culling in front of it,
//               the work culling saves.
// Set-up, untimed: ours' sets (computed once per environment on the config's visibility backend,
// and kept: plain data) and one
// run of the phase, which sizes its buffers.
#include <map>
#include <string>

#include "bench/BenchmarkSuite.h"
#include "culling/exact/ExactPhase.h"
#include "culling/visibility/VisibilityBackendRegistry.h"
#include "harness/measure/BackendWarmUp.h"

namespace cdb::bench {

namespace {

constexpr int kSetsResolution = 800;

const PotentiallyCollidingSets& oursSets(RecordedFrames& frames, const std::string& environment) {
  static std::map<std::string, PotentiallyCollidingSets> kept;
  auto found = kept.find(environment);
  if (found != kept.end()) return found->second;
  const RecordedScene& recorded = frames.recorded(environment);
  const FrameInput input{frames.poses(environment), frames.measured(environment).frame};
  const auto owned = VisibilityBackendRegistry::builtin().create(
      backendNameOf(recorded.config.culling), frames.resources(),
      visibilityOptionsOf(recorded.config.culling));
  VisibilityBackend& backend = *owned;
  backend.attachScene(recorded.scene);
  warmUpBackend(backend, recorded.scene, input.poses, kSetsResolution);
  auto ours =
      DetectorRegistry::builtin().create("ours", DetectorOptions{kSetsResolution, recorded.config.culling});
  ours->attach(recorded.scene, backend);
  (void)ours->cull(input);  // the sets of a strategy that has seen a frame before, as timed
  return kept.emplace(environment, ours->cull(input).sets).first->second;
}

// The sets of the registered brute-force reference (every object in one set).
PotentiallyCollidingSets allPairsSets(RecordedFrames& frames, const std::string& environment) {
  const RecordedScene& recorded = frames.recorded(environment);
  auto reference =
      DetectorRegistry::builtin().create("all_pairs", DetectorOptions{kSetsResolution, recorded.config.culling});
  const auto backend = VisibilityBackendRegistry::builtin().create(
      backendNameOf(recorded.config.culling), frames.resources(), {});
  reference->attach(recorded.scene, *backend);
  return reference->cull({frames.poses(environment), frames.measured(environment).frame}).sets;
}

void runExactPhase(benchmark::State& state, const SceneGeometry& scene, std::span<const Pose> poses,
                   const PotentiallyCollidingSets& sets) {
  ExactPhase exact(scene);
  (void)exact.run(poses, sets);
  CollisionReport total;
  std::uint64_t collidingPairs = 0;
  for (auto _ : state) {
    const CollisionReport report = exact.run(poses, sets);
    total.pairsTested += report.pairsTested;
    total.triangleTests += report.triangleTests;
    total.collidingTrianglePairs += report.collidingTrianglePairs;
    collidingPairs += report.collidingPairs.size();
  }
  std::uint64_t members = 0;
  for (const PotentiallyCollidingSet& set : sets) members += set.members.size();
  state.counters["sets"] = double(sets.size());
  state.counters["set_objects"] = double(members);
  state.counters["pairs_tested"] = perIteration(double(total.pairsTested));
  state.counters["triangle_tests"] = perIteration(double(total.triangleTests));
  state.counters["colliding_pairs"] = perIteration(double(collidingPairs));
  state.counters["colliding_triangle_pairs"] = perIteration(double(total.collidingTrianglePairs));
}

}  // namespace

void registerExactPhaseBenchmarks(RecordedFrames& frames) {
  for (const MeasuredFrame& m : frames.frames()) {
    const std::string prefix = "exact/" + m.environment;
    registerMilliseconds(prefix + "/ours_sets", [&frames, environment = m.environment](
                                                    benchmark::State& state) {
      const PotentiallyCollidingSets& sets = oursSets(frames, environment);
      runExactPhase(state, frames.recorded(environment).scene, frames.poses(environment), sets);
    });
    registerMilliseconds(prefix + "/all_pairs_sets", [&frames, environment = m.environment](
                                                         benchmark::State& state) {
      runExactPhase(state, frames.recorded(environment).scene, frames.poses(environment),
                    allPairsSets(frames, environment));
    });
  }
}

}  // namespace cdb::bench
