#pragma once
// A recorded pose stream: every object's pose for every frame of one simulation, so that every
// strategy and resolution of a run replays exactly the same frames. File format: see
// docs/pose-recording.md.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "core/Pose.h"
#include "scenes/ScenarioConfig.h"
#include "scenes/SceneGeometry.h"

namespace cdb {

struct PoseRecording {
  std::string environment;
  std::uint64_t fingerprint = 0;  // scenarioFingerprint() of the config and scene it came from
  std::uint64_t seed = 0;
  std::uint32_t objectCount = 0;
  std::vector<Pose> poses;  // frame-major: frame f, object i at poses[f * objectCount + i]

  [[nodiscard]] std::uint32_t frameCount() const {
    return objectCount ? static_cast<std::uint32_t>(poses.size() / objectCount) : 0;
  }
  [[nodiscard]] std::span<const Pose> frame(std::uint32_t f) const {
    return std::span<const Pose>(poses).subspan(std::size_t(f) * objectCount, objectCount);
  }
  // FNV-1a over the raw bytes of every pose: equal hashes mean bit-identical streams.
  [[nodiscard]] std::uint64_t hash() const;
};

// What determines the frames: dynamics, bodies, counts, meshes (sizes and triangle counts).
// A recording is refused for a config whose fingerprint differs.
[[nodiscard]] std::uint64_t scenarioFingerprint(const ScenarioConfig& config, const SceneGeometry& scene);

// Simulates config.dynamics.frames frames (after warm-up) with RigidBodySimulation.
[[nodiscard]] PoseRecording recordSimulation(const ScenarioConfig& config, const SceneGeometry& scene,
                                             std::uint64_t seed);

// Written atomically (temporary file, then rename). Throws RunError when it cannot write.
void writePoseRecording(const PoseRecording& recording, const std::filesystem::path& file);
// Throws InputError naming the file and what is wrong (not a recording, truncated, bad version).
[[nodiscard]] PoseRecording readPoseRecording(const std::filesystem::path& file);
// The same from the bytes of a recording already in memory; `name` stands for the file in messages.
[[nodiscard]] PoseRecording readPoseRecordingFromBytes(std::span<const char> bytes,
                                                       const std::string& name);

}  // namespace cdb
