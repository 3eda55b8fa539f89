#include "harness/measure/RecordedScene.h"

#include "core/Errors.h"
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

std::span<const Pose> recordedPoses(const RecordedScene& recorded, int frame, std::string_view scene) {
  const std::uint32_t frames = recorded.recording.frameCount();
  if (frame < 0 || static_cast<std::uint32_t>(frame) >= frames)
    throw InputError((scene.empty() ? std::string() : std::string(scene) + ": ") + "frame " +
                     std::to_string(frame) + " out of the " + std::to_string(frames) + " simulated");
  return recorded.recording.frame(static_cast<std::uint32_t>(frame));
}

}  // namespace cdb
