#include "harness/check/CheckScenes.h"

#include "scenes/AssetPath.h"
#include "scenes/ConfigLoader.h"
#include "scenes/SceneBuilder.h"

namespace cdb {

CheckScenes::CheckScenes(std::filesystem::path configDir, std::vector<std::string> assetDirs)
    : configDir_(std::move(configDir)), assetDirs_(assetSearchPath(assetDirs)) {}

const RecordedScene& CheckScenes::get(const CheckScene& spec) {
  for (const auto& e : entries_)
    if (e.spec == spec) return *e.recorded;
  auto r = std::make_unique<RecordedScene>();
  r->config = loadScenarioConfig(configDir_ / spec.config);
  // withObjectCount sets the swept group's count; env1 and env2 sweep resolutions, not counts.
  r->config.sweep.countedGroup = spec.group;
  r->config = withObjectCount(r->config, spec.objects);
  r->config.seed = spec.seed;
  // The check guards the default, conservative mode (no real contact lost at any resolution),
  // whatever the config says: raw mode loses contacts by design (README "Visibility backends").
  r->config.culling.visibility.conservative = true;
  r->config.dynamics.frames = spec.frames;
  r->scene = buildScene(r->config, assetDirs_);
  r->recording = recordSimulation(r->config, r->scene, spec.seed);
  entries_.push_back({spec, std::move(r)});
  return *entries_.back().recorded;
}

}  // namespace cdb
