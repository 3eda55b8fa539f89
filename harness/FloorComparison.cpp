#include "harness/FloorComparison.h"

#include <algorithm>
#include <chrono>

#include "harness/BackendWarmUp.h"

namespace cdb {

namespace {

template <typename F>
double secondsOf(F&& work) {
  const auto t0 = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

VisibilityCounters recordCullWork(RecordingBackend& recorder, const RecordedScene& recorded,
                                  const std::string& strategyName, int resolution, int frame,
                                  const StrategyRegistry& registry) {
  const auto poses = recordedPoses(recorded, frame);
  StrategyOptions so;
  so.resolution = resolution;
  so.culling = recorded.config.culling;
  auto strategy = registry.create(strategyName, so);
  strategy->attach(recorded.scene, recorder);
  (void)strategy->cull({poses, frame});
  recorder.clear();
  recorder.attachScene(recorded.scene);
  recorder.resetCounters();
  (void)strategy->cull({poses, frame});
  return recorder.counters();
}

FloorSetup::FloorSetup(BackendResources& resources, const std::string& backend,
                       const RecordedScene& recorded, const std::string& strategy, int resolution,
                       int frame, const StrategyRegistry& registry)
    : recorded_(recorded), frame_(frame) {
  const auto poses = recordedPoses(recorded, frame);
  const auto& backends = VisibilityBackendRegistry::builtin();
  const VisibilityOptions options = visibilityOptionsOf(recorded.config.culling);
  backend_ = backends.create(backend, resources, options);
  backend_->attachScene(recorded.scene);
  warmUpBackend(*backend_, recorded.scene, poses, resolution);
  recorder_ = std::make_unique<RecordingBackend>(*backend_);
  work_ = recordCullWork(*recorder_, recorded, strategy, resolution, frame, registry);

  // The strategy alone, on the bare backend, with the same history.
  StrategyOptions so;
  so.resolution = resolution;
  so.culling = recorded.config.culling;
  strategy_ = registry.create(strategy, so);
  strategy_->attach(recorded.scene, *backend_);
  (void)strategy_->cull({poses, frame});

  floor_ = backends.createFloor(backend, resources, options);
  floor_->prepare(recorder_->ops());
  floor_->replayOnce();
}

double FloorSetup::timeCull() {
  return secondsOf([&] { (void)strategy_->cull({recordedPoses(recorded_, frame_), frame_}); });
}

double FloorSetup::timeFloor() { return secondsOf([&] { floor_->replayOnce(); }); }

FloorComparison compareWithFloor(BackendResources& resources, const std::string& backend,
                                 const RecordedScene& recorded, const std::string& strategyName,
                                 int resolution, int frame, int repeats,
                                 const StrategyRegistry& registry) {
  repeats = std::max(repeats, 1);
  FloorSetup setup(resources, backend, recorded, strategyName, resolution, frame, registry);
  FloorComparison c;
  c.work = setup.work();
  c.answersMatch = setup.answersMatch();
  c.strategyBestSeconds = c.floorBestSeconds = 1e300;
  for (int r = 0; r < repeats; ++r) {
    // In turn, so that both sides of a round see the same load on a shared machine.
    const double cull = setup.timeCull();
    const double floor = setup.timeFloor();
    c.answersMatch = c.answersMatch && setup.answersMatch();
    c.strategyBestSeconds = std::min(c.strategyBestSeconds, cull);
    c.floorBestSeconds = std::min(c.floorBestSeconds, floor);
    c.strategyMeanSeconds += cull / repeats;
    c.floorMeanSeconds += floor / repeats;
  }
  return c;
}

}  // namespace cdb
