#pragma once
// A culling strategy: a frame of poses in, potentially colliding sets and counters out, for the
// exact phase to test. A strategy is created by name from the DetectorRegistry, attached once to a
// scene and a visibility backend, then called once per frame; the harness times it inside an
// ImageBasedDetector (culling/CollisionDetector.h).
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "culling/PotentiallyCollidingSets.h"
#include "culling/exact/ObjectPair.h"
#include "culling/visibility/VisibilityBackend.h"
#include "core/Pose.h"
#include "scenes/ScenarioConfig.h"
#include "scenes/SceneGeometry.h"

namespace cdb {

// One level of a coarse-to-fine traversal of the objects' bounding-volume hierarchies.
struct LevelCounters {
  std::uint32_t level = 0;         // depth in the hierarchies (0 = the roots)
  std::uint64_t nodesTested = 0;   // active nodes entering the level's visibility tests
  std::uint64_t nodesKept = 0;     // active nodes left after them
  std::uint64_t sets = 0;          // potentially colliding sets left after them
  std::uint64_t queries = 0;       // occlusion queries the level issued
};

struct CullingCounters {
  VisibilityCounters visibility;
  std::uint64_t pcsSize = 0;   // objects left in some set after culling
  std::uint64_t sets = 0;      // number of potentially colliding (collision-independent) sets
  std::uint64_t pcsTriangles = 0;  // triangles left for the exact phase
  std::vector<LevelCounters> levels;  // strategies with a hierarchy: one entry per level
};

struct CullingResult {
  PotentiallyCollidingSets sets;
  CullingCounters counters;
};

struct FrameInput {
  std::span<const Pose> poses;  // one per object of the attached scene
  int frame = 0;
};

class CullingStrategy {
 public:
  virtual ~CullingStrategy() = default;
  [[nodiscard]] virtual std::string_view name() const = 0;
  // Per-scene preparation (hierarchies, resident geometry). The backend outlives the strategy.
  virtual void attach(const SceneGeometry& scene, VisibilityBackend& backend) = 0;
  [[nodiscard]] virtual CullingResult cull(const FrameInput& frame) = 0;
};

}  // namespace cdb
