#pragma once
// An image-based detector: a culling strategy asks a visibility backend which objects may touch,
// then the exact phase tests what the culling left. The all_pairs reference is built the same way
// (its strategy culls nothing and asks no backend).
#include <memory>

#include "culling/CollisionDetector.h"
#include "culling/CullingStrategy.h"
#include "culling/exact/ExactPhase.h"
#include "culling/visibility/VisibilityBackend.h"

namespace cdb {

class ImageBasedDetector final : public CollisionDetector {
 public:
  // The backend and the exact phase outlive the detector; `exact` must be built for the scene the
  // detector is attached to.
  ImageBasedDetector(std::unique_ptr<CullingStrategy> strategy, VisibilityBackend& backend,
                     ExactPhase& exact);

  [[nodiscard]] std::string_view name() const override { return strategy_->name(); }
  void attach(const SceneGeometry& scene) override { strategy_->attach(scene, backend_); }
  [[nodiscard]] DetectedFrame detect(const FrameInput& frame) override;

 private:
  std::unique_ptr<CullingStrategy> strategy_;
  VisibilityBackend& backend_;
  ExactPhase& exact_;
};

}  // namespace cdb
