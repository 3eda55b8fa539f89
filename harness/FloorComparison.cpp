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

FloorComparison compareWithFloor(HeadlessGlContext& gl, const RecordedScene& recorded,
                                 const std::string& strategyName, int resolution, int frame,
                                 int repeats, const StrategyRegistry& registry) {
  if (frame < 0 || static_cast<std::uint32_t>(frame) >= recorded.recording.frameCount())
    throw InputError("frame " + std::to_string(frame) + ": the recording has " +
                     std::to_string(recorded.recording.frameCount()) + " frames");
  repeats = std::max(repeats, 1);
  const auto poses = recorded.recording.frame(static_cast<std::uint32_t>(frame));
  const VisibilityOptions options{recorded.config.culling.conservative,
                                  recorded.config.culling.rawDepthOffset};
  StrategyOptions so;
  so.resolution = resolution;
  so.culling = recorded.config.culling;

  GlOcclusionQueryBackend backend(gl, options);
  backend.attachScene(recorded.scene);
  warmUpBackend(backend, recorded.scene, poses, resolution);

  // The work, recorded from a second cull of the frame.
  RecordingBackend recorder(backend);
  auto recordingStrategy = registry.create(strategyName, so);
  recordingStrategy->attach(recorded.scene, recorder);
  (void)recordingStrategy->cull({poses, frame});
  recorder.clear();
  recorder.attachScene(recorded.scene);  // the floor replays a self-contained recording
  backend.resetCounters();
  (void)recordingStrategy->cull({poses, frame});
  FloorComparison c;
  c.work = backend.counters();

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
