#include "harness/check/CheckCorrectness.h"

#include "culling/exact/ExactPhase.h"
#include "culling/exact/GroundTruth.h"
#include "culling/visibility/VisibilityBackendRegistry.h"
#include "harness/measure/BackendWarmUp.h"

namespace cdb {

std::vector<CorrectnessRow> checkCorrectness(BackendResources& resources, const std::string& backendName,
                                             bool withPeers, CheckScenes& scenes,
                                             const std::vector<CorrectnessCase>& cases,
                                             const std::vector<std::string>& strategies,
                                             const DetectorRegistry& registry) {
  std::vector<CorrectnessRow> rows;
  for (const auto& c : cases) {
    const RecordedScene& recorded = scenes.get(c.scene);
    for (int f : c.frames) (void)recordedPoses(recorded, f, c.scene.label());
    const SceneGeometry& scene = recorded.scene;
    const auto backend = VisibilityBackendRegistry::builtin().create(
        backendName, resources, visibilityOptionsOf(recorded.config.culling));
    backend->attachScene(scene);
    ExactPhase exact(scene);
    std::vector<std::vector<ObjectPair>> truth;
    {
      const GroundTruth reference(scene);
      for (int f : c.frames)
        truth.push_back(reference.compute(recorded.recording.frame(static_cast<std::uint32_t>(f)))
                            .collidingPairs);
    }

    for (const auto& name : strategies) {
      // What draws nothing (CPU peers, the reference) runs once: no backend, no resolution
      // enters its answer.
      const bool drawsNothing = !registry.usesBackend(name);
      if (drawsNothing && !withPeers) continue;
      for (int resolution : c.resolutions) {
        auto detector = registry.createDetector(
            name, DetectorOptions{resolution, recorded.config.culling}, *backend, exact);
        detector->attach(scene);
        warmUpBackend(*backend, scene, recorded.recording.frame(0), resolution);
        for (std::size_t i = 0; i < c.frames.size(); ++i) {
          const int f = c.frames[i];
          const DetectedFrame detected =
              detector->detect({recorded.recording.frame(static_cast<std::uint32_t>(f)), f});
          CorrectnessRow row;
          row.backend = drawsNothing ? "-" : backendName;
          row.scene = c.scene.label();
          row.frame = f;
          row.strategy = name;
          row.resolution = drawsNothing ? 0 : resolution;
          row.truthPairs = truth[i].size();
          row.foundPairs = detected.report.collidingPairs.size();
          row.comparison = compareWithTruth(truth[i], detected, scene.objectCount());
          rows.push_back(std::move(row));
        }
        if (drawsNothing) break;
      }
    }
  }
  return rows;
}

}  // namespace cdb
