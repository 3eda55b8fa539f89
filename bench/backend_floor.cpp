// The backend's floor for one strategy on one recorded frame: the strategy's culling time against
// the same draws, queries and fetches replayed as plain GL commands with no algorithm around them
// (GlDrawFloor). Their ratio is the strategy's overhead over what the backend must do anyway.
//
//   cdbench_floor CONFIG --strategy cullide --resolution 800 --frame 150 [--objects N] [--repeats 3]
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/Errors.h"
#include "culling/StrategyRegistry.h"
#include "culling/visibility/GlDrawFloor.h"
#include "culling/visibility/GlOcclusionQueryBackend.h"
#include "culling/visibility/RecordingBackend.h"
#include "render/HeadlessGlContext.h"
#include "scenes/AssetPath.h"
#include "scenes/ConfigLoader.h"
#include "scenes/PoseRecording.h"
#include "scenes/SceneBuilder.h"

int main(int argc, char** argv) {
  CLI::App app{"backend floor: a strategy's culling time against its own GL work replayed bare"};
  std::string config, strategyName = "cullide";
  std::vector<std::string> assets;
  int resolution = 800, frame = 150, objects = 0, repeats = 3;
  app.add_option("config", config)->required();
  app.add_option("--strategy", strategyName);
  app.add_option("--resolution", resolution);
  app.add_option("--frame", frame, "simulated frame to measure");
  app.add_option("--objects", objects, "count of the swept group (0: the config's)");
  app.add_option("--repeats", repeats);
  app.add_option("--assets", assets);
  CLI11_PARSE(app, argc, argv);
  try {
    using namespace cdb;
    ScenarioConfig cfg = loadScenarioConfig(config);
    if (objects > 0) cfg = withObjectCount(cfg, objects);
    cfg.dynamics.frames = frame + 1;
    const SceneGeometry scene = buildScene(cfg, assetSearchPath(assets));
    const PoseRecording recording = recordSimulation(cfg, scene, cfg.seed);
    const auto poses = recording.frame(static_cast<std::uint32_t>(frame));

    HeadlessGlContext gl(GlPlatform::Auto);
    const VisibilityOptions options{cfg.culling.conservative, cfg.culling.rawDepthOffset};
    GlOcclusionQueryBackend backend(gl, options);
    RecordingBackend recorder(backend);
    recorder.attachScene(scene);
    StrategyOptions so;
    so.resolution = resolution;
    so.culling = cfg.culling;
    auto strategy = StrategyRegistry::builtin().create(strategyName, so);
    strategy->attach(scene, recorder);
    (void)strategy->cull({poses, frame});  // warm-up: shader variants, caches

    double best = 1e300, sum = 0;
    for (int r = 0; r < repeats; ++r) {
      recorder.clear();
      recorder.attachScene(scene);  // the floor replays a self-contained recording
      const auto t0 = std::chrono::steady_clock::now();
      (void)strategy->cull({poses, frame});
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      best = std::min(best, s);
      sum += s;
    }
    GlDrawFloor floor(gl, options);
    const FloorTiming t = floor.replay(recorder.ops(), repeats);
    std::printf("renderer: %s\n", gl.info().glRenderer.c_str());
    std::printf("%s %s res=%d frame=%d: %zu queries, %zu draws, %zu passes, %zu fetches\n",
                cfg.environment.c_str(), strategyName.c_str(), resolution, frame, t.queries, t.draws,
                t.passes, t.fetches);
    std::printf("strategy cull: best %.2f ms, mean %.2f ms\n", best * 1e3, sum / repeats * 1e3);
    std::printf("backend floor: best %.2f ms, mean %.2f ms (answers %s)\n", t.bestSeconds * 1e3,
                t.meanSeconds * 1e3, t.answersMatch ? "match" : "DIFFER");
    std::printf("ratio strategy/floor (best): %.3f\n", best / t.bestSeconds);
    return t.answersMatch ? 0 : 1;
  } catch (const cdb::InputError& e) {
    std::fprintf(stderr, "cdbench_floor: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cdbench_floor: failed: %s\n", e.what());
    return 1;
  }
}
