#pragma once
// FCL (Flexible Collision Library) as a peer: its dynamic AABB tree broad phase over one
// OBBRSS bounding-volume hierarchy per mesh, and fcl::collide on each broad-phase pair.
#include <memory>

#include "culling/peers/CpuPeer.h"
#include "culling/DetectorRegistry.h"

namespace cdb {

class FclPeer final : public CpuPeer {
 public:
  explicit FclPeer(const DetectorOptions& options);
  ~FclPeer() override;

  [[nodiscard]] std::string_view name() const override { return "fcl"; }
  void attach(const SceneGeometry& scene) override;

 private:
  [[nodiscard]] LibraryPairs collide(std::span<const Pose> poses) override;
  struct Impl;  // keeps FCL's headers out of the harness
  std::unique_ptr<Impl> impl_;
};

}  // namespace cdb
