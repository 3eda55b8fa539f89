#pragma once
// Small scenarios for the dynamics and recording tests: a torus group, a floor plane, a cube.
#include <string>
#include <vector>

#include "scenes/ProceduralMeshes.h"
#include "scenes/SceneBuilder.h"
#include "scenes/ScenarioConfig.h"
#include "scenes/SceneGeometry.h"

namespace cdb::dynamics_test {

inline BodyGroup torusGroup(std::string name, int count) {
  BodyGroup group;
  group.name = std::move(name);
  group.mesh.kind = MeshSpec::Kind::Torus;  // R 0.5, r 0.2, 20 x 20: the thesis' 800 triangles
  group.count = count;
  return group;
}

inline BodyGroup floorGroup(double y = 0.0) {
  BodyGroup group;
  group.name = "floor";
  group.mesh.kind = MeshSpec::Kind::Plane;
  group.mesh.planeSize = 8.0;
  group.fixed = true;
  group.poses = {InitialPose{{0, y, 0}, {0, 0, 0}}};
  return group;
}

inline InitialPose at(double x, double y, double z, Vec3 degrees = {0, 0, 0}) {
  return InitialPose{{x, y, z}, degrees};
}

// Tori flying freely in a closed cube without gravity, as in env3.
inline ScenarioConfig cubeScenario(int tori, double halfExtent = 2.5) {
  ScenarioConfig config;
  config.environment = "cube-test";
  config.seed = 7;
  config.dynamics.gravity = {0, 0, 0};
  config.dynamics.containerHalfExtent = halfExtent;
  config.dynamics.restitution = 0.5;
  BodyGroup group = torusGroup("torus", tori);
  RandomPlacement placement;
  const double r = halfExtent - 0.75;
  placement.regionMin = {-r, -r, -r};
  placement.regionMax = {r, r, r};
  placement.minGap = 0.02;
  placement.speedMin = 1.0;
  placement.speedMax = 3.0;
  placement.angularSpeedMax = 2.0;
  group.placement = placement;
  config.bodies = {group};
  return config;
}

// Tori dropped in a column onto a fixed floor, as in env1.
inline ScenarioConfig dropScenario(std::vector<InitialPose> toriPoses) {
  ScenarioConfig config;
  config.environment = "drop-test";
  BodyGroup tori = torusGroup("torus", int(toriPoses.size()));
  tori.poses = std::move(toriPoses);
  config.bodies = {floorGroup(), tori};
  return config;
}

// Procedural meshes only, so no asset path.
inline SceneGeometry sceneFor(const ScenarioConfig& config) { return buildScene(config, {}); }

}  // namespace cdb::dynamics_test
