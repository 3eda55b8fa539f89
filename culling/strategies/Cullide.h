#pragma once
// CULLIDE without a hierarchy (Govindaraju, Redon, Lin, Manocha 2003; thesis 2.4 and Chapter 4):
// two-pass visibility pruning at object level (pass 1 in order O1..On, pass 2 in reverse; an
// object fully visible in both passes leaves the PCS) along x, y and z, then the same at
// sub-object (triangle) level on the objects left. One potentially colliding set comes out.
#include <array>
#include <vector>

#include "culling/CullingStrategy.h"
#include "culling/DetectorRegistry.h"
#include "culling/TwoPassPruning.h"
#include "culling/WorldBounds.h"

namespace cdb {

class Cullide final : public CullingStrategy {
 public:
  explicit Cullide(const DetectorOptions& options);

  [[nodiscard]] std::string_view name() const override { return "cullide"; }
  void attach(const SceneGeometry& scene, VisibilityBackend& backend) override;
  [[nodiscard]] CullingResult cull(const FrameInput& frame) override;

 private:
  void pruneObjects(std::vector<ObjectId>& pcs, const Eigen::Vector3d& axis);
  void pruneTriangles(std::vector<SetMember>& members, const Eigen::Vector3d& axis);

  DetectorOptions options_;
  const SceneGeometry* scene_ = nullptr;
  VisibilityBackend* backend_ = nullptr;
  WorldBounds bounds_;
  TwoPassAnswers visible_;  // query answers, reused across frames
};

}  // namespace cdb
