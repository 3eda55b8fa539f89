#pragma once
// Scenes for the exact-phase tests: tori at random poses, dense enough that many interpenetrate,
// and the world transform the exact phase and the ground truth apply to vertices.
#include <cstdint>
#include <random>
#include <vector>

#include "core/Pose.h"
#include "scenes/ProceduralMeshes.h"
#include "scenes/SceneGeometry.h"

namespace cdb::testing {

// Unoptimised (debug, sanitizer) builds run the scene tests on fewer frames and seeds.
#ifdef NDEBUG
inline constexpr int kRepeats = 3;
#else
inline constexpr int kRepeats = 1;
#endif

inline Pose randomPose(std::mt19937_64& rng, double boxSide) {
  std::uniform_real_distribution<double> u(0.0, boxSide);
  std::normal_distribution<double> g;
  Pose p;
  p.rotation = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
  p.translation = {u(rng), u(rng), u(rng)};
  return p;
}

// `count` objects of one torus mesh; `frames` independent random pose sets in a cube of `boxSide`.
struct ToriScene {
  SceneGeometry scene;
  std::vector<std::vector<Pose>> frames;
};

inline ToriScene randomTori(int count, double boxSide, int frames, std::uint64_t seed,
                            int rings = 20, int sides = 20) {
  ToriScene s;
  s.scene.meshes.push_back(makeTorus(0.5, 0.2, rings, sides));
  for (int i = 0; i < count; ++i) s.scene.objects.push_back({0, false, "torus"});
  std::mt19937_64 rng(seed);
  for (int f = 0; f < frames; ++f) {
    std::vector<Pose> poses;
    for (int i = 0; i < count; ++i) poses.push_back(randomPose(rng, boxSide));
    s.frames.push_back(std::move(poses));
  }
  return s;
}

// The world transform in the form the exact phase and the ground truth use, so that brute-force
// references in the tests see bit-identical coordinates.
inline std::vector<Eigen::Vector3d> worldVertices(const Mesh& mesh, const Pose& pose) {
  const Eigen::Matrix3d r = pose.rotation.toRotationMatrix();
  std::vector<Eigen::Vector3d> out(mesh.vertices.size());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    out[v] = r * mesh.vertices[v].cast<double>() + pose.translation;
  return out;
}

// An axis-aligned unit cube [0, 1]^3, 12 triangles.
inline Mesh unitCube() {
  Mesh m;
  m.name = "cube";
  for (int i = 0; i < 8; ++i)
    m.vertices.emplace_back(float(i & 1), float((i >> 1) & 1), float(i >> 2));
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

}  // namespace cdb::testing
