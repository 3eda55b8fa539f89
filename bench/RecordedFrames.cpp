#include "bench/RecordedFrames.h"

#include "core/Errors.h"
#include "culling/visibility/VisibilityBackendRegistry.h"
#include "scenes/AssetPath.h"
#include "scenes/ConfigLoader.h"
#include "scenes/SceneBuilder.h"

namespace cdb::bench {

std::vector<MeasuredFrame> defaultMeasuredFrames() {
  return {{"env1", 0, 150}, {"env2", 0, 200}, {"env3", 200, 147}};
}

RecordedFrames::RecordedFrames(std::filesystem::path configDir, std::vector<std::string> assetDirs,
                               GlPlatform platform, std::vector<MeasuredFrame> frames)
    : configDir_(std::move(configDir)),
      assetDirs_(std::move(assetDirs)),
      frames_(std::move(frames)),
      resources_(platform) {
  const auto& registry = VisibilityBackendRegistry::builtin();
  std::vector<std::string> why;
  backends_ = registry.available(resources_, &why);
  for (const auto& name : backends_)
    backendDescription_ += (backendDescription_.empty() ? "" : "; ") + name + " on " +
                           registry.create(name, resources_, {})->renderer();
  for (const auto& w : why) backendDescription_ += (backendDescription_.empty() ? "" : "; ") + w;
}

const MeasuredFrame& RecordedFrames::measured(const std::string& environment) const {
  for (const MeasuredFrame& f : frames_)
    if (f.environment == environment) return f;
  throw InputError("no measured frame for environment '" + environment + "'");
}

std::filesystem::path RecordedFrames::configPath(const std::string& environment) const {
  return configDir_ / (environment + ".yaml");
}

const RecordedScene& RecordedFrames::recorded(const std::string& environment) {
  auto found = recorded_.find(environment);
  if (found == recorded_.end()) {
    const MeasuredFrame& m = measured(environment);
    found = recorded_
                .emplace(environment,
                         recordScene(configPath(environment), m.objects, m.frame + 1, assetDirs_))
                .first;
  }
  return found->second;
}

std::span<const Pose> RecordedFrames::poses(const std::string& environment) {
  return recorded(environment)
      .recording.frame(static_cast<std::uint32_t>(measured(environment).frame));
}

const RecordedScene& RecordedFrames::unsimulated(const std::string& environment) {
  auto found = unsimulated_.find(environment);
  if (found == unsimulated_.end()) {
    RecordedScene r;
    r.config = loadScenarioConfig(configPath(environment));
    r.scene = buildScene(r.config, assetSearchPath(assetDirs_));
    found = unsimulated_.emplace(environment, std::move(r)).first;
  }
  return found->second;
}

}  // namespace cdb::bench
