#pragma once
// The exact phase shared by every image-based strategy: inside each potentially colliding set,
// sweep-and-prune on world AABBs of the members, then triangle-triangle tests (double precision,
// robust) between the surviving member pairs, restricted to each member's triangle subset. A set
// that lists its pairs (PotentiallyCollidingSet::pairs) has only those pairs swept, each side
// restricted further to the pair's own triangles.
#include <memory>
#include <span>

#include "core/Pose.h"
#include "culling/PotentiallyCollidingSets.h"
#include "culling/exact/ObjectPair.h"
#include "scenes/SceneGeometry.h"

namespace cdb {

class ExactPhase {
 public:
  // Caches per-mesh data; `scene` must outlive the phase. With several threads (0: every core)
  // the members of a set are prepared, and its pairs tested, on that many; what is found and
  // counted is the same at any number.
  explicit ExactPhase(const SceneGeometry& scene, int threads = 1);
  ~ExactPhase();
  ExactPhase(ExactPhase&&) noexcept;
  // `poses` holds one pose per scene object. An object pair found in several sets is reported
  // once; once found colliding, later sets skip it.
  [[nodiscard]] CollisionReport run(std::span<const Pose> poses,
                                    const PotentiallyCollidingSets& sets);

 private:
  struct Workspace;  // per-mesh caches and buffers reused from frame to frame
  const SceneGeometry& scene_;
  std::unique_ptr<Workspace> work_;
};

}  // namespace cdb
