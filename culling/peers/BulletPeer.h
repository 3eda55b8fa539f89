#pragma once
// Bullet (3.24, built in double precision) as a peer: a collision world with the dynamic AABB
// tree broad phase (btDbvtBroadphase) and GImpact triangle meshes, Bullet's concave-concave
// collider. It does the whole collision detection on the CPU and ignores the visibility backend.
#include <memory>

#include "culling/CullingStrategy.h"
#include "culling/StrategyRegistry.h"

namespace cdb {

class BulletPeer final : public CullingStrategy {
 public:
  explicit BulletPeer(const StrategyOptions& options);
  ~BulletPeer() override;

  [[nodiscard]] std::string_view name() const override { return "bullet"; }
  void attach(const SceneGeometry& scene, VisibilityBackend& backend) override;
  [[nodiscard]] CullingResult cull(const FrameInput& frame) override;

 private:
  struct Impl;  // keeps Bullet's headers (and its precision define) out of the harness
  std::unique_ptr<Impl> impl_;
};

}  // namespace cdb
