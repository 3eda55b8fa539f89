#pragma once
// CULLIDE's answer computed order-independently (not in any paper; named cullide_oi). CULLIDE's
// two passes are sequential by construction: each piece is tested against the pieces drawn before
// it, then drawn, so an axis is a chain of about 4n draws with an answer between each test and the
// next draw. But the answer it uses does not depend on the order, taken over both passes: a piece
// is fully visible in pass 1 when, at every pixel it covers, its test depth lies in front of the
// nearest written depth of the pieces before it, and in pass 2 of those after it; so it is fully
// visible in both exactly when, at every pixel, its test depth lies in front of the nearest depth
// written by every other object. Per pixel that needs the nearest written depth d1 with its object
// id1, and d2, the nearest written depth of any object but id1; a piece of object i fails at a
// pixel where its test depth is not in front of (id1 == i ? d2 : d1). One pass of the backend
// (DepthUse::OrderIndependent) writes every piece, then tests every piece: a few draws per axis
// instead of ~4n, no answer needed in between, every pixel independent. With the same
// conservative depths (tests the farthest over a pixel, writes the nearest), the potentially
// colliding set after each axis and level is exactly CULLIDE's.
//
// Axes, levels and pruning flow are CULLIDE's (culling/strategies/Cullide.h): object level along
// x, y, z, then triangle level on the objects left (an object's own triangles never occlude it).
#include <vector>

#include "culling/CullingStrategy.h"
#include "culling/DetectorRegistry.h"
#include "culling/PotentiallyCollidingSets.h"
#include "culling/WorldBounds.h"

namespace cdb {

class OrderIndependentCullide final : public CullingStrategy {
 public:
  explicit OrderIndependentCullide(const DetectorOptions& options);

  [[nodiscard]] std::string_view name() const override { return "cullide_oi"; }
  // InputError when the backend offers no order-independent pass.
  void attach(const SceneGeometry& scene, VisibilityBackend& backend) override;
  [[nodiscard]] CullingResult cull(const FrameInput& frame) override;

 private:
  void pruneObjects(std::vector<ObjectId>& pcs, const Eigen::Vector3d& axis);
  void pruneTriangles(std::vector<SetMember>& members, const Eigen::Vector3d& axis);

  DetectorOptions options_;
  const SceneGeometry* scene_ = nullptr;
  VisibilityBackend* backend_ = nullptr;
  WorldBounds bounds_;
  std::vector<std::uint8_t> visible_;  // answers, reused across frames
};

}  // namespace cdb
