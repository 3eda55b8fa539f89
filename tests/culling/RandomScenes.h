#pragma once
// Random test scenes: tori (optionally with two planes, or dragons) at random poses in a box
// small enough that many of them touch or interpenetrate.
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "core/Pose.h"
#include "scenes/MeshLoader.h"
#include "scenes/ProceduralMeshes.h"
#include "scenes/SceneGeometry.h"

namespace cdb::testing {

struct RandomScene {
  SceneGeometry scene;
  std::vector<std::vector<Pose>> frames;  // a few random frames
};

inline Pose randomPose(std::mt19937_64& rng, double halfExtent) {
  std::uniform_real_distribution<double> u(-halfExtent, halfExtent);
  std::normal_distribution<double> g;
  Pose p;
  p.rotation = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
  p.translation = {u(rng), u(rng), u(rng)};
  return p;
}

inline RandomScene randomTori(int tori, double halfExtent, int frames, std::uint64_t seed,
                              bool withPlanes = false) {
  RandomScene s;
  s.scene.meshes.push_back(makeTorus(0.5, 0.2, 20, 20));
  for (int i = 0; i < tori; ++i) s.scene.objects.push_back({0, false, "torus"});
  if (withPlanes) {
    s.scene.meshes.push_back(makePlane(2.0 * halfExtent + 1.0, 30));
    s.scene.objects.push_back({1, true, "plane"});
    s.scene.objects.push_back({1, true, "plane"});
  }
  std::mt19937_64 rng(seed);
  for (int f = 0; f < frames; ++f) {
    std::vector<Pose> poses;
    for (int i = 0; i < tori; ++i) poses.push_back(randomPose(rng, halfExtent));
    if (withPlanes) {
      Pose floor;  // through the middle of the tori, so it cuts several of them
      floor.rotation = Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX());
      Pose ramp;
      ramp.rotation = Eigen::AngleAxisd(-0.5, Eigen::Vector3d::UnitZ());
      ramp.translation = {0, 0.3, 0};
      poses.push_back(floor);
      poses.push_back(ramp);
    }
    s.frames.push_back(std::move(poses));
  }
  return s;
}

// The dragon from the asset path, or nothing when it is not there.
inline std::optional<std::filesystem::path> findDragon() {
  std::vector<std::filesystem::path> dirs;
  if (const char* env = std::getenv("CDBENCH_ASSETS")) {
    std::string all = env;
    std::size_t start = 0;
    while (start <= all.size()) {
      const auto end = all.find(':', start);
      dirs.emplace_back(all.substr(start, end - start));
      if (end == std::string::npos) break;
      start = end + 1;
    }
  }
#ifdef CDBENCH_SOURCE_DIR
  dirs.emplace_back(std::filesystem::path(CDBENCH_SOURCE_DIR) / ".." / "shared" / "meshes");
  dirs.emplace_back(std::filesystem::path(CDBENCH_SOURCE_DIR) / "assets");
#endif
  for (const auto& d : dirs)
    for (const char* ext : {".obj", ".ply"})
      if (std::filesystem::exists(d / (std::string("dragon_vrip_res3") + ext)))
        return d / (std::string("dragon_vrip_res3") + ext);
  return std::nullopt;
}

}  // namespace cdb::testing
