#pragma once
// The independent reference: every object pair, a CPU bounding-volume tree per mesh, and the same
// exact triangle test as the exact phase (its only shared code). Not part of any CD time.
#include <memory>
#include <span>

#include "core/Pose.h"
#include "culling/exact/ObjectPair.h"
#include "scenes/SceneGeometry.h"

namespace cdb {

class GroundTruth {
 public:
  explicit GroundTruth(const SceneGeometry& scene);  // builds the per-mesh trees once
  ~GroundTruth();
  GroundTruth(GroundTruth&&) noexcept;
  [[nodiscard]] CollisionReport compute(std::span<const Pose> poses) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cdb
