#pragma once
// ODE as a peer: its own broad phase (a multi-resolution hash space) over one dGeomTriMesh
// per object, and dCollide with OPCODE's trimesh-trimesh collider on each pair the space reports.
// This is ODE's collision detection only: the dynamics that record the frames live in
// scenes/RigidBodySimulation.
#include <memory>

#include "culling/peers/CpuPeer.h"
#include "culling/DetectorRegistry.h"

namespace cdb {

class OdePeer final : public CpuPeer {
 public:
  explicit OdePeer(const DetectorOptions& options);
  ~OdePeer() override;

  [[nodiscard]] std::string_view name() const override { return "ode"; }
  void attach(const SceneGeometry& scene) override;

 private:
  [[nodiscard]] LibraryPairs collide(std::span<const Pose> poses) override;
  struct Impl;  // keeps ODE's headers out of the harness
  std::unique_ptr<Impl> impl_;
};

}  // namespace cdb
