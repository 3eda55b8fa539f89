#include "harness/CheckCorrectness.h"

#include "core/Errors.h"
#include "culling/exact/ExactPhase.h"
#include "culling/exact/GroundTruth.h"
#include "culling/visibility/GlOcclusionQueryBackend.h"
#include "harness/BackendWarmUp.h"

namespace cdb {

std::vector<CorrectnessRow> checkCorrectness(HeadlessGlContext& gl, CheckScenes& scenes,
                                             const std::vector<CorrectnessCase>& cases,
                                             const std::vector<std::string>& strategies,
                                             const StrategyRegistry& registry) {
  std::vector<CorrectnessRow> rows;
  for (const auto& c : cases) {
    const RecordedScene& recorded = scenes.get(c.scene);
    for (int f : c.frames)
      if (f < 0 || static_cast<std::uint32_t>(f) >= recorded.recording.frameCount())
        throw InputError(c.scene.label() + ": frame " + std::to_string(f) + " out of the " +
                         std::to_string(recorded.recording.frameCount()) + " simulated");
    const SceneGeometry& scene = recorded.scene;
    GlOcclusionQueryBackend backend(
        gl, {recorded.config.culling.conservative, recorded.config.culling.rawDepthOffset});
    backend.attachScene(scene);
    ExactPhase exact(scene);
    std::vector<std::vector<ObjectPair>> truth;
    {
      const GroundTruth reference(scene);
      for (int f : c.frames)
        truth.push_back(reference.compute(recorded.recording.frame(static_cast<std::uint32_t>(f)))
                            .collidingPairs);
    }

    for (const auto& name : strategies) {
      for (int resolution : c.resolutions) {
        StrategyOptions options;
        options.resolution = resolution;
        options.culling = recorded.config.culling;
        auto strategy = registry.create(name, options);
        strategy->attach(scene, backend);
        warmUpBackend(backend, scene, recorded.recording.frame(0), resolution);
        bool decidedItself = false;
        for (std::size_t i = 0; i < c.frames.size(); ++i) {
          const int f = c.frames[i];
          const auto poses = recorded.recording.frame(static_cast<std::uint32_t>(f));
          CullingResult culled = strategy->cull({poses, f});
          decidedItself = culled.decided.has_value();
          const CollisionReport report =
              decidedItself ? std::move(*culled.decided) : exact.run(poses, culled.sets);
          CorrectnessRow row;
          row.scene = c.scene.label();
          row.frame = f;
          row.strategy = name;
          row.resolution = decidedItself ? 0 : resolution;
          row.truthPairs = truth[i].size();
          row.foundPairs = report.collidingPairs.size();
          row.comparison = compareWithTruth(truth[i], report.collidingPairs, culled, scene.objectCount());
          rows.push_back(std::move(row));
        }
        if (decidedItself) break;
      }
    }
  }
  return rows;
}

}  // namespace cdb
