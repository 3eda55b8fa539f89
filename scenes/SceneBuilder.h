#pragma once
// Turns a scenario config into the scene geometry: one mesh per body group (shared by its
// bodies), objects in group order (group 0's bodies first).
#include <string>
#include <vector>

#include "scenes/ScenarioConfig.h"
#include "scenes/SceneGeometry.h"

namespace cdb {

// `assetDirs` is the asset search path (see AssetPath.h). Throws InputError for a missing or
// invalid mesh.
[[nodiscard]] SceneGeometry buildScene(const ScenarioConfig& config,
                                       const std::vector<std::string>& assetDirs);

// The config with the swept group's count set to `count` (sweep.countedGroup).
[[nodiscard]] ScenarioConfig withObjectCount(const ScenarioConfig& config, int count);

}  // namespace cdb
