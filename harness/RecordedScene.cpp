#include "harness/RecordedScene.h"

#include "scenes/AssetPath.h"
#include "scenes/ConfigLoader.h"
#include "scenes/SceneBuilder.h"

namespace cdb {

RecordedScene recordScene(const std::filesystem::path& configPath, int objects, int frames,
                          const std::vector<std::string>& assetDirs) {
  RecordedScene r;
  r.config = loadScenarioConfig(configPath);
  if (objects > 0) r.config = withObjectCount(r.config, objects);
  if (frames > 0) r.config.dynamics.frames = frames;
  r.scene = buildScene(r.config, assetSearchPath(assetDirs));
  r.recording = recordSimulation(r.config, r.scene, r.config.seed);
  return r;
}

}  // namespace cdb
