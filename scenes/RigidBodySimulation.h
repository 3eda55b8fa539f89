#pragma once
// The dynamics of a scenario, stepped by ODE: bodies with mass properties from their meshes (or
// their proxies), trimesh contact (or a proxy chosen in the config), fixed bodies, the closed cube
// of env3, and seeded random placement and velocities. Same config and seed: bit-identical poses.
#include <cstdint>
#include <memory>
#include <span>

#include "core/Pose.h"
#include "scenes/ScenarioConfig.h"
#include "scenes/SceneGeometry.h"

namespace cdb {

class RigidBodySimulation {
 public:
  // `scene` must come from buildScene(config) and outlive the simulation.
  RigidBodySimulation(const ScenarioConfig& config, const SceneGeometry& scene, std::uint64_t seed);
  ~RigidBodySimulation();
  RigidBodySimulation(const RigidBodySimulation&) = delete;
  RigidBodySimulation& operator=(const RigidBodySimulation&) = delete;

  // Advances one frame (dynamics.stepsPerFrame ODE steps). Throws RunError naming the frame and
  // the body when a pose becomes NaN or explodes.
  void stepFrame();
  [[nodiscard]] std::span<const Pose> poses() const;  // one per object, current frame
  [[nodiscard]] int frame() const;                    // frames stepped so far

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cdb
