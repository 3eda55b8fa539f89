#include "harness/measure/FloorComparison.h"

#include <algorithm>
#include <chrono>

#include "harness/measure/BackendWarmUp.h"

namespace cdb {

namespace {

template <typename F>
double secondsOf(F&& work) {
  const auto t0 = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// A new `name` on `backend` that has culled `frame` once, so that a strategy keeping state across
// frames (sorted lists, hierarchies) meets the frame as it would in a run.
std::unique_ptr<CullingStrategy> strategyAfterOneCull(const DetectorRegistry& registry,
                                                      const std::string& name,
                                                      const RecordedScene& recorded, int resolution,
                                                      VisibilityBackend& backend, int frame) {
  auto strategy = registry.create(name, DetectorOptions{resolution, recorded.config.culling});
  strategy->attach(recorded.scene, backend);
  (void)strategy->cull({recordedPoses(recorded, frame), frame});
  return strategy;
}

}  // namespace

VisibilityCounters recordCullWork(RecordingBackend& recorder, const RecordedScene& recorded,
                                  const std::string& strategyName, int resolution, int frame,
                                  const DetectorRegistry& registry) {
  const auto poses = recordedPoses(recorded, frame);
  const auto strategy =
      strategyAfterOneCull(registry, strategyName, recorded, resolution, recorder, frame);
  recorder.clear();
  recorder.attachScene(recorded.scene);
  recorder.resetCounters();
  (void)strategy->cull({poses, frame});
  return recorder.counters();
}

FloorSetup::FloorSetup(BackendResources& resources, const std::string& backend,
                       const RecordedScene& recorded, const std::string& strategy, int resolution,
                       int frame, const DetectorRegistry& registry)
    : recorded_(recorded), frame_(frame) {
  backend_ = warmedUpBackend(resources, backend, recorded.config.culling, recorded.scene,
                             recordedPoses(recorded, frame), resolution);
  recorder_ = std::make_unique<RecordingBackend>(*backend_);
  work_ = recordCullWork(*recorder_, recorded, strategy, resolution, frame, registry);

  // The strategy alone, on the bare backend, with the same history.
  strategy_ = strategyAfterOneCull(registry, strategy, recorded, resolution, *backend_, frame);

  floor_ = VisibilityBackendRegistry::builtin().createFloor(
      backend, resources, visibilityOptionsOf(recorded.config.culling));
  floor_->prepare(recorder_->ops());
  floor_->replayOnce();
}

double FloorSetup::timeCull() {
  return secondsOf([&] { (void)strategy_->cull({recordedPoses(recorded_, frame_), frame_}); });
}

double FloorSetup::timeFloor() { return secondsOf([&] { floor_->replayOnce(); }); }

FloorSetup::Round FloorSetup::timeRound(bool floorFirst) {
  Round r;
  if (floorFirst) {
    r.floorSeconds = timeFloor();
    r.cullSeconds = timeCull();
  } else {
    r.cullSeconds = timeCull();
    r.floorSeconds = timeFloor();
  }
  r.answersMatch = answersMatch();
  return r;
}

FloorComparison compareWithFloor(BackendResources& resources, const std::string& backend,
                                 const RecordedScene& recorded, const std::string& strategyName,
                                 int resolution, int frame, int repeats,
                                 const DetectorRegistry& registry) {
  repeats = std::max(repeats, 1);
  FloorSetup setup(resources, backend, recorded, strategyName, resolution, frame, registry);
  FloorComparison c;
  c.work = setup.work();
  c.answersMatch = setup.answersMatch();
  c.strategyBestSeconds = c.floorBestSeconds = 1e300;
  for (int r = 0; r < repeats; ++r) {
    // In turn, so that both sides of a round see the same load on a shared machine.
    const FloorSetup::Round round = setup.timeRound();
    const double cull = round.cullSeconds;
    const double floor = round.floorSeconds;
    c.answersMatch = c.answersMatch && round.answersMatch;
    c.strategyBestSeconds = std::min(c.strategyBestSeconds, cull);
    c.floorBestSeconds = std::min(c.floorBestSeconds, floor);
    c.strategyMeanSeconds += cull / repeats;
    c.floorMeanSeconds += floor / repeats;
  }
  return c;
}

}  // namespace cdb
