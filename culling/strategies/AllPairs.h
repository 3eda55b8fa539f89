#pragma once
// The brute-force reference: every object in one set, no visibility test, so the exact phase
// (sweep-and-prune inside the set, then triangle tests) does the whole job alone. The baseline
// row of every table: what culling saves is all_pairs' time minus a strategy's. Brute-force
// broad phases of other libraries are the same reference (Jolt's BroadPhaseBruteForce, FCL's
// NaiveCollisionManager).
#include "culling/CullingStrategy.h"
#include "culling/DetectorRegistry.h"

namespace cdb {

class AllPairs final : public CullingStrategy {
 public:
  explicit AllPairs(const DetectorOptions& /*options*/) {}
  [[nodiscard]] std::string_view name() const override { return "all_pairs"; }
  // The backend is not used: nothing is drawn.
  void attach(const SceneGeometry& scene, VisibilityBackend& backend) override;
  [[nodiscard]] CullingResult cull(const FrameInput& frame) override;

 private:
  const SceneGeometry* scene_ = nullptr;
};

}  // namespace cdb
