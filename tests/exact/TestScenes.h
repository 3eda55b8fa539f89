#pragma once
// Scenes for the exact-phase tests: tori at random poses, dense enough that many interpenetrate,
// and the world transform the exact phase and the ground truth apply to vertices.
#include <cstdint>
#include <vector>

#include "core/Pose.h"
#include "scenes/SceneGeometry.h"
#include "tests/common/RandomScenes.h"

namespace cdb::testing {

// Unoptimised (debug, sanitizer) builds run the scene tests on fewer frames and seeds.
#ifdef NDEBUG
inline constexpr int kRepeats = 3;
#else
inline constexpr int kRepeats = 1;
#endif

// `count` objects of one torus mesh; `frames` independent random pose sets in [0, boxSide)^3.
inline RandomScene randomTori(int count, double boxSide, int frames, std::uint64_t seed,
                              int rings = 20, int sides = 20) {
  RandomToriSpec spec;
  spec.count = count;
  spec.lo = 0.0;
  spec.hi = boxSide;
  spec.frames = frames;
  spec.seed = seed;
  spec.rings = rings;
  spec.sides = sides;
  return randomTori(spec);
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

// `count` objects of one unitCube() mesh, each at the origin until a test poses it.
inline SceneGeometry unitCubes(int count) {
  SceneGeometry scene;
  scene.meshes.push_back(unitCube());
  for (int i = 0; i < count; ++i) scene.objects.push_back({0, false, "cube"});
  return scene;
}

}  // namespace cdb::testing
