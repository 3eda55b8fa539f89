#pragma once
// Bullet (built in double precision) as a peer: a collision world with the dynamic AABB
// tree broad phase (btDbvtBroadphase) and GImpact triangle meshes, Bullet's concave-concave
// collider.
#include <memory>

#include "culling/peers/CpuPeer.h"
#include "culling/DetectorRegistry.h"

namespace cdb {

class BulletPeer final : public CpuPeer {
 public:
  explicit BulletPeer(const DetectorOptions& options);
  ~BulletPeer() override;

  [[nodiscard]] std::string_view name() const override { return "bullet"; }
  void attach(const SceneGeometry& scene) override;

 private:
  [[nodiscard]] LibraryPairs collide(std::span<const Pose> poses) override;
  struct Impl;  // keeps Bullet's headers (and its precision define) out of the harness
  std::unique_ptr<Impl> impl_;
};

}  // namespace cdb
