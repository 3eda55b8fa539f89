#include "harness/FloorComparison.h"

#include <algorithm>
#include <chrono>

#include "core/Errors.h"
#include "culling/StrategyRegistry.h"
#include "culling/visibility/GlDrawFloor.h"
#include "culling/visibility/GlOcclusionQueryBackend.h"
#include "culling/visibility/RecordingBackend.h"
#include "harness/BackendWarmUp.h"

namespace cdb {

namespace {

std::span<const Pose> posesOf(const RecordedScene& recorded, int frame) {
  if (frame < 0 || static_cast<std::uint32_t>(frame) >= recorded.recording.frameCount())
    throw InputError("frame " + std::to_string(frame) + ": the recording has " +
                     std::to_string(recorded.recording.frameCount()) + " frames");
  return recorded.recording.frame(static_cast<std::uint32_t>(frame));
}

}  // namespace

VisibilityCounters recordCullWork(RecordingBackend& recorder, const RecordedScene& recorded,
                                  const std::string& strategyName, int resolution, int frame,
                                  const StrategyRegistry& registry) {
  const auto poses = posesOf(recorded, frame);
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

FloorComparison compareWithFloor(HeadlessGlContext& gl, const RecordedScene& recorded,
                                 const std::string& strategyName, int resolution, int frame,
                                 int repeats, const StrategyRegistry& registry) {
  const auto poses = posesOf(recorded, frame);
  repeats = std::max(repeats, 1);
  const VisibilityOptions options{recorded.config.culling.conservative,
                                  recorded.config.culling.rawDepthOffset};
  StrategyOptions so;
  so.resolution = resolution;
  so.culling = recorded.config.culling;

  GlOcclusionQueryBackend backend(gl, options);
  backend.attachScene(recorded.scene);
  warmUpBackend(backend, recorded.scene, poses, resolution);

  RecordingBackend recorder(backend);
  FloorComparison c;
  c.work = recordCullWork(recorder, recorded, strategyName, resolution, frame, registry);

  // The strategy alone, on the bare backend, with the same history.
  auto strategy = registry.create(strategyName, so);
  strategy->attach(recorded.scene, backend);
  (void)strategy->cull({poses, frame});
  double best = 1e300, sum = 0;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    (void)strategy->cull({poses, frame});
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    best = std::min(best, s);
    sum += s;
  }
  c.strategyBestSeconds = best;
  c.strategyMeanSeconds = sum / repeats;

  GlDrawFloor floor(gl, options);
  const FloorTiming t = floor.replay(recorder.ops(), repeats);
  c.floorBestSeconds = t.bestSeconds;
  c.floorMeanSeconds = t.meanSeconds;
  c.answersMatch = t.answersMatch;
  return c;
}

}  // namespace cdb
