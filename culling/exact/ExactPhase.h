#pragma once
// The exact phase shared by every image-based strategy: inside each potentially colliding set,
// sweep-and-prune on world AABBs of the members, then triangle-triangle tests (double precision,
// robust) between the surviving member pairs, restricted to each member's triangle subset.
#include <span>

#include "core/Pose.h"
#include "culling/PotentiallyCollidingSets.h"
#include "culling/exact/ObjectPair.h"
#include "scenes/SceneGeometry.h"

namespace cdb {

class ExactPhase {
 public:
  explicit ExactPhase(const SceneGeometry& scene);
  [[nodiscard]] CollisionReport run(std::span<const Pose> poses, const PotentiallyCollidingSets& sets);

 private:
  const SceneGeometry& scene_;
};

}  // namespace cdb
