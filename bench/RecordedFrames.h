#pragma once
// What the micro-benchmarks measure on: one recorded frame per environment in which objects touch.
// An environment's config is simulated on first use by a selected benchmark and kept for the rest
// of the run, so a --benchmark_filter that selects only BVH builds simulates nothing. One set of
// backend resources (one GL context, opened up front) serves every benchmark of every backend. Benchmarks run one at a time on the main
// thread, so nothing here locks.
#include <filesystem>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "culling/visibility/BackendResources.h"
#include "harness/measure/RecordedScene.h"

namespace cdb::bench {

// One environment's measured frame.
struct MeasuredFrame {
  std::string environment;  // env1, env2 or env3: the config is <config dir>/<environment>.yaml
  int objects = 0;          // count of the config's swept group (0 keeps the config's)
  int frame = 0;            // the simulated frame measured (0 is the first)
};

// The frames measured unless overridden (touching pairs as the ground truth of `cdbench run`
// counts them, seed 1; exact/<env>/all_pairs_sets reports them as colliding_pairs, so a config
// change that moves the contacts shows there):
//  env1, frame 150 (3 s): the config's 50 tori have settled into a pile in the trough's crease;
//    113 object pairs touch (tori with tori and with the planes).
//  env2, frame 200 (4 s): the 12 dragons have settled into a pile about two deep; 25 pairs touch
//    (dragons with dragons and with the planes). CULLIDE issues ~3 million occlusion queries per
//    cull of this frame, 30-55 s on llvmpipe with 2 cores.
//  env3, 200 tori, frame 147 (~3 s): the tori have crossed the cube a few times since their
//    random start and 4 pairs touch, as many as in any frame after the first two seconds.
[[nodiscard]] std::vector<MeasuredFrame> defaultMeasuredFrames();

class RecordedFrames {
 public:
  // Opens the GL context on `platform` now (a failure leaves the GL backends out of backends(), so
  // the other benchmarks still run) and simulates nothing yet. `assetDirs` as for
  // `cdbench run --assets`.
  RecordedFrames(std::filesystem::path configDir, std::vector<std::string> assetDirs,
                 GlPlatform platform, std::vector<MeasuredFrame> frames);

  [[nodiscard]] const std::vector<MeasuredFrame>& frames() const { return frames_; }
  [[nodiscard]] const MeasuredFrame& measured(const std::string& environment) const;
  [[nodiscard]] std::filesystem::path configPath(const std::string& environment) const;

  // The environment's config simulated up to its measured frame, on the first call. Throws
  // InputError for a bad config or a missing mesh (the dragon: CDBENCH_ASSETS), RunError for a
  // simulation that goes unstable.
  [[nodiscard]] const RecordedScene& recorded(const std::string& environment);
  // The poses of the measured frame.
  [[nodiscard]] std::span<const Pose> poses(const std::string& environment);

  // The environment's config and scene, not simulated (the recording is empty): its meshes and
  // tree options, for the BVH build.
  [[nodiscard]] const RecordedScene& unsimulated(const std::string& environment);

  [[nodiscard]] BackendResources& resources() { return resources_; }
  // The visibility backends that start here, in registry order.
  [[nodiscard]] const std::vector<std::string>& backends() const { return backends_; }
  // Each backend's renderer, or why it does not start (for the JSON context).
  [[nodiscard]] std::string backendDescription() const { return backendDescription_; }

 private:
  std::filesystem::path configDir_;
  std::vector<std::string> assetDirs_;
  std::vector<MeasuredFrame> frames_;
  BackendResources resources_;
  std::vector<std::string> backends_;
  std::string backendDescription_;
  std::map<std::string, RecordedScene> recorded_;
  std::map<std::string, RecordedScene> unsimulated_;
};

}  // namespace cdb::bench
