#pragma once
// Random test scenes: one torus mesh at random poses, dense enough that many touch or
// interpenetrate. Each suite states its own region (tests/culling centres it on the origin,
// tests/exact puts it in the positive octant).
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "core/Pose.h"
#include "scenes/ProceduralMeshes.h"
#include "scenes/SceneGeometry.h"

namespace cdb::testing {

struct RandomScene {
  SceneGeometry scene;
  std::vector<std::vector<Pose>> frames;  // independent random pose sets
};

// A uniformly random rotation and a translation uniform in [lo, hi)^3.
inline Pose randomPose(std::mt19937_64& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  std::normal_distribution<double> g;
  Pose p;
  p.rotation = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
  p.translation = {u(rng), u(rng), u(rng)};
  return p;
}

struct RandomToriSpec {
  int count = 0;
  double lo = 0, hi = 1;  // the translations' cube [lo, hi)^3
  int frames = 1;
  std::uint64_t seed = 0;
  int rings = 20, sides = 20;  // of the torus mesh (radii 0.5 and 0.2)
  // Two static planes after the tori: a floor through the origin and a ramp, each as wide as
  // the cube plus one, so that they cut several tori.
  bool withPlanes = false;
};

inline RandomScene randomTori(const RandomToriSpec& spec) {
  RandomScene s;
  s.scene.meshes.push_back(makeTorus(0.5, 0.2, spec.rings, spec.sides));
  for (int i = 0; i < spec.count; ++i) s.scene.objects.push_back({0, false, "torus"});
  if (spec.withPlanes) {
    s.scene.meshes.push_back(makePlane(spec.hi - spec.lo + 1.0, 30));
    s.scene.objects.push_back({1, true, "plane"});
    s.scene.objects.push_back({1, true, "plane"});
  }
  std::mt19937_64 rng(spec.seed);
  for (int f = 0; f < spec.frames; ++f) {
    std::vector<Pose> poses;
    for (int i = 0; i < spec.count; ++i) poses.push_back(randomPose(rng, spec.lo, spec.hi));
    if (spec.withPlanes) {
      Pose floor;
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

}  // namespace cdb::testing
