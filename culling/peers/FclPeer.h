#pragma once
// FCL (Flexible Collision Library, 0.7) as a peer: its dynamic AABB tree broad phase over one
// OBBRSS bounding-volume hierarchy per mesh, and fcl::collide on each broad-phase pair. It does the
// whole collision detection on the CPU and ignores the visibility backend.
#include <memory>

#include "culling/CullingStrategy.h"
#include "culling/StrategyRegistry.h"

namespace cdb {

class FclPeer final : public CullingStrategy {
 public:
  explicit FclPeer(const StrategyOptions& options);
  ~FclPeer() override;

  [[nodiscard]] std::string_view name() const override { return "fcl"; }
  void attach(const SceneGeometry& scene, VisibilityBackend& backend) override;
  [[nodiscard]] CullingResult cull(const FrameInput& frame) override;

 private:
  struct Impl;  // keeps FCL's headers out of the harness
  std::unique_ptr<Impl> impl_;
};

}  // namespace cdb
