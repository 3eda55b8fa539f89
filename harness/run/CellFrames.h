#pragma once
// What the cells of a run are measured on: the scene of an object count (geometry, the exact
// phase's caches, the ground truth) and the frames of an (object count, repeat), simulated once
// (or read back from the run folder or from --replay), with the ground truth's pairs on every
// measured frame. Consecutive cells of one simulation share all of it.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "culling/exact/ExactPhase.h"
#include "culling/exact/GroundTruth.h"
#include "culling/visibility/VisibilityBackend.h"
#include "harness/run/CellStore.h"
#include "harness/run/RunOptions.h"
#include "harness/run/RunPlan.h"
#include "harness/run/WallTimeBreakdown.h"
#include "scenes/AssetFiles.h"
#include "scenes/PoseRecording.h"
#include "scenes/ScenarioConfig.h"
#include "scenes/SceneGeometry.h"

namespace cdb {

class CellFrames {
 public:
  // Every reference must outlive this object; `backend` is attached to each scene built, and the
  // time spent is added to `time` (set-up, simulation, truth).
  CellFrames(const ScenarioConfig& config, const RunOptions& options, const CellStore& store,
             std::vector<std::string> assetDirs, VisibilityBackend& backend,
             WallTimeBreakdown& time);

  // Makes `cell`'s scene and frames current: the scene is rebuilt when the object count changes,
  // the frames when the (object count, repeat) does.
  void prepare(const Cell& cell);

  // The config with the current cell's object count.
  [[nodiscard]] const ScenarioConfig& config() const { return *cellConfig_; }
  [[nodiscard]] const SceneGeometry& scene() const { return *scene_; }
  [[nodiscard]] ExactPhase& exact() { return *exact_; }
  [[nodiscard]] int movingObjects() const { return movingObjects_; }
  [[nodiscard]] const PoseRecording& recording() const { return recording_; }
  // Frame indices timed in every cell of the current simulation (every frame-stride-th).
  [[nodiscard]] const std::vector<std::uint32_t>& measuredFrames() const { return measured_; }
  [[nodiscard]] bool hasTruth() const { return truth_.has_value(); }
  // The ground truth's colliding pairs on a measured frame (empty without a truth).
  [[nodiscard]] const std::vector<ObjectPair>& truthPairs(std::uint32_t frame) const {
    return truthPairs_[frame];
  }
  // Whether a scene was built, and the asset files the scenes built so far were loaded from (each
  // asset and file once, hashed as they were loaded).
  [[nodiscard]] bool builtAScene() const { return sceneCount_.has_value(); }
  [[nodiscard]] const std::vector<AssetFile>& loadedAssets() const { return assets_; }

 private:
  void buildScene(int objectCount);
  void loadFrames(const Cell& cell);

  const ScenarioConfig& base_;
  const RunOptions& options_;
  const CellStore& store_;
  std::vector<std::string> assetDirs_;  // the asset search path, in order
  VisibilityBackend& backend_;
  WallTimeBreakdown& time_;

  std::optional<int> sceneCount_;
  std::optional<ScenarioConfig> cellConfig_;
  std::optional<SceneGeometry> scene_;
  std::vector<AssetFile> assets_;
  std::optional<ExactPhase> exact_;
  std::optional<GroundTruth> truth_;
  int movingObjects_ = 0;
  std::optional<Cell> framesOf_;
  PoseRecording recording_;
  std::vector<std::uint32_t> measured_;
  std::vector<std::vector<ObjectPair>> truthPairs_;
};

}  // namespace cdb
