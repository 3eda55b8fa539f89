// The backend's floor for one strategy on one recorded frame: the strategy's culling time against
// the same backend work issued again with no algorithm around it (BackendFloor: bare GL commands
// for gl-queries, the recorded calls replayed for the other backends), each cull followed by a
// replay, `repeats` times. Their ratio is the strategy's overhead over what the backend must do
// anyway.
//
//   cdbench_floor CONFIG --strategy cullide --resolution 800 --frame 150 [--visibility gl-queries]
//                 [--objects N] [--repeats 3]
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/Errors.h"
#include "culling/visibility/VisibilityBackendRegistry.h"
#include "harness/measure/FloorComparison.h"
#include "harness/measure/RecordedScene.h"

int main(int argc, char** argv) {
  CLI::App app{"backend floor: a strategy's culling time against its own GL work replayed bare"};
  std::string config, strategyName = "cullide", backend(cdb::VisibilityBackendRegistry::kDefault);
  std::vector<std::string> assets;
  int resolution = 800, frame = 150, objects = 0, repeats = 3;
  app.add_option("config", config)->required();
  app.add_option("--strategy", strategyName);
  app.add_option("--visibility", backend, "visibility backend (cdbench backends)");
  app.add_option("--resolution", resolution);
  app.add_option("--frame", frame, "simulated frame to measure");
  app.add_option("--objects", objects, "count of the swept group (0: the config's)");
  app.add_option("--repeats", repeats);
  app.add_option("--assets", assets);
  CLI11_PARSE(app, argc, argv);
  try {
    using namespace cdb;
    const RecordedScene recorded = recordScene(config, objects, frame + 1, assets);
    BackendResources resources(GlPlatform::Auto);
    const FloorComparison c =
        compareWithFloor(resources, backend, recorded, strategyName, resolution, frame, repeats);
    std::printf("backend: %s on %s\n", backend.c_str(),
                VisibilityBackendRegistry::builtin().create(backend, resources, {})->renderer().c_str());
    std::printf("%s %s res=%d frame=%d: %llu queries, %llu draws, %llu passes, %llu fetches\n",
                recorded.config.environment.c_str(), strategyName.c_str(), resolution, frame,
                static_cast<unsigned long long>(c.work.queries),
                static_cast<unsigned long long>(c.work.draws),
                static_cast<unsigned long long>(c.work.passes),
                static_cast<unsigned long long>(c.work.fetches));
    std::printf("strategy cull: best %.2f ms, mean %.2f ms\n", c.strategyBestSeconds * 1e3,
                c.strategyMeanSeconds * 1e3);
    std::printf("backend floor: best %.2f ms, mean %.2f ms (answers %s)\n", c.floorBestSeconds * 1e3,
                c.floorMeanSeconds * 1e3, c.answersMatch ? "match" : "DIFFER");
    std::printf("ratio strategy/floor (best): %.3f\n", c.ratio());
    return c.answersMatch ? 0 : 1;
  } catch (const cdb::InputError& e) {
    std::fprintf(stderr, "cdbench_floor: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cdbench_floor: failed: %s\n", e.what());
    return 1;
  }
}
