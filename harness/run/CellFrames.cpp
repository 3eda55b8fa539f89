#include "harness/run/CellFrames.h"

#include "core/Errors.h"
#include "scenes/SceneBuilder.h"

namespace cdb {

namespace {

int countMovingBodies(const SceneGeometry& scene) {
  int n = 0;
  for (const auto& o : scene.objects) n += o.fixed ? 0 : 1;
  return n;
}

// The recording of a cell's (object count, repeat): replayed from --replay, reused from the run
// folder when an earlier invocation (or another share) simulated it, else simulated now and kept
// there.
PoseRecording framesFor(const Cell& cell, const ScenarioConfig& cfg, const SceneGeometry& scene,
                        const RunOptions& options, const CellStore& store) {
  const std::uint64_t fingerprint = scenarioFingerprint(cfg, scene);
  if (options.replayFile) {
    PoseRecording r = readPoseRecording(*options.replayFile);
    if (r.fingerprint != fingerprint || r.objectCount != scene.objectCount())
      throw InputError(options.replayFile->string() +
                       ": recording was made from another config (fingerprint or object count differs)");
    if (r.frameCount() == 0) throw InputError(options.replayFile->string() + ": holds no frame");
    return r;
  }
  const auto kept = store.recordingPath(cell);
  const std::uint64_t seed = cfg.seed + static_cast<std::uint64_t>(cell.repeat);
  if (std::filesystem::exists(kept)) {
    try {
      PoseRecording r = readPoseRecording(kept);
      if (r.fingerprint == fingerprint && r.seed == seed &&
          r.frameCount() == static_cast<std::uint32_t>(cfg.dynamics.frames))
        return r;
    } catch (const InputError&) {
      // A damaged leftover is simulated again below.
    }
  }
  PoseRecording r = recordSimulation(cfg, scene, seed);
  writePoseRecording(r, kept);
  return r;
}

}  // namespace

CellFrames::CellFrames(const ScenarioConfig& config, const RunOptions& options,
                       const CellStore& store, std::vector<std::string> assetDirs,
                       VisibilityBackend& backend, WallTimeBreakdown& time)
    : base_(config),
      options_(options),
      store_(store),
      assetDirs_(std::move(assetDirs)),
      backend_(backend),
      time_(time) {}

void CellFrames::prepare(const Cell& cell) {
  if (!sceneCount_ || *sceneCount_ != cell.objectCount) buildScene(cell.objectCount);
  if (!framesOf_ || !framesOf_->sameFrames(cell)) loadFrames(cell);
}

void CellFrames::buildScene(int objectCount) {
  {
    const ScopedSeconds timed(time_.setupSeconds);
    sceneCount_ = objectCount;
    cellConfig_ = objectCount < 0 ? base_ : withObjectCount(base_, objectCount);
    exact_.reset();
    truth_.reset();
    scene_ = cdb::buildScene(*cellConfig_, assetDirs_);
    for (AssetFile& f : assetFiles(*cellConfig_, *scene_, assets_)) assets_.push_back(std::move(f));
    movingObjects_ = countMovingBodies(*scene_);
    exact_.emplace(*scene_, cellConfig_->culling.visibility.threads);
    backend_.attachScene(*scene_);
    framesOf_.reset();
  }
  const ScopedSeconds timed(time_.truthSeconds);
  if (options_.groundTruth) truth_.emplace(*scene_);
}

void CellFrames::loadFrames(const Cell& cell) {
  framesOf_ = cell;
  {
    const ScopedSeconds timed(time_.simulationSeconds);
    recording_ = framesFor(cell, *cellConfig_, *scene_, options_, store_);
  }
  if (options_.recordFile) writePoseRecording(recording_, *options_.recordFile);
  measured_.clear();
  const auto stride = static_cast<std::uint32_t>(options_.frameStride);
  for (std::uint32_t f = 0; f < recording_.frameCount(); f += stride) measured_.push_back(f);
  truthPairs_.assign(recording_.frameCount(), {});
  const ScopedSeconds timed(time_.truthSeconds);
  if (truth_)
    for (std::uint32_t f : measured_) truthPairs_[f] = truth_->compute(recording_.frame(f)).collidingPairs;
}

}  // namespace cdb
