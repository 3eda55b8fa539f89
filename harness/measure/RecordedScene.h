#pragma once
// A scenario config simulated once and kept in memory: the scene and every frame's poses, so that
// benchmarks and checks run strategies on exactly the frames a `cdbench run` would measure.
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "scenes/PoseRecording.h"
#include "scenes/ScenarioConfig.h"
#include "scenes/SceneGeometry.h"

namespace cdb {

struct RecordedScene {
  ScenarioConfig config;
  SceneGeometry scene;
  PoseRecording recording;
};

// Loads `configPath`, sets the swept group's count to `objects` (0 keeps the config's), and
// simulates `frames` frames (0 keeps the config's) with the config's seed. `assetDirs` as for
// `--assets` (CDBENCH_ASSETS and <repo>/assets follow). Throws InputError for a bad config or mesh.
[[nodiscard]] RecordedScene recordScene(const std::filesystem::path& configPath, int objects = 0,
                                        int frames = 0, const std::vector<std::string>& assetDirs = {});

// The poses of `frame` of `recorded`. Throws InputError, prefixed by `scene` when given, for a frame
// the recording does not hold (checks and floor comparisons take frame numbers from their input).
[[nodiscard]] std::span<const Pose> recordedPoses(const RecordedScene& recorded, int frame,
                                                  std::string_view scene = {});

}  // namespace cdb
