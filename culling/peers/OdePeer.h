#pragma once
// ODE (0.16) as a peer: its own broad phase (a multi-resolution hash space) over one dGeomTriMesh
// per object, and dCollide with OPCODE's trimesh-trimesh collider on each pair the space reports.
// It does the whole collision detection on the CPU and ignores the visibility backend. This is
// ODE's collision detection only: the dynamics that record the frames live in
// scenes/RigidBodySimulation.
#include <memory>

#include "culling/CullingStrategy.h"
#include "culling/StrategyRegistry.h"

namespace cdb {

class OdePeer final : public CullingStrategy {
 public:
  explicit OdePeer(const StrategyOptions& options);
  ~OdePeer() override;

  [[nodiscard]] std::string_view name() const override { return "ode"; }
  void attach(const SceneGeometry& scene, VisibilityBackend& backend) override;
  [[nodiscard]] CullingResult cull(const FrameInput& frame) override;

 private:
  struct Impl;  // keeps ODE's headers out of the harness
  std::unique_ptr<Impl> impl_;
};

}  // namespace cdb
