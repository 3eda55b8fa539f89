#pragma once
// CULLIDE over a bounding-volume hierarchy (thesis Chapter 4, "CULLIDE with BVH"; CULLIDE's
// pruning as in 2.4, each object's 8-ary OBB tree as in 3.4.1): the pruning runs coarse to fine.
// Level 0 tests every object's root box; at each level, along x, y and z in turn, two passes
// with a fresh depth buffer each (pass 1 in order O1..On, pass 2 in reverse) test and draw each
// object's active nodes; a node fully visible in both passes is pruned, an object left with no
// node leaves. The surviving nodes are then expanded, until every active node is a leaf. One
// potentially colliding set comes out, its members restricted to the surviving leaves'
// triangles.
#include <cstdint>
#include <vector>

#include "core/GrowOnlyArray.h"
#include "culling/CullingStrategy.h"
#include "culling/DetectorRegistry.h"
#include "culling/TwoPassPruning.h"
#include "culling/bvh/NodeFrontier.h"
#include "culling/bvh/SceneHierarchies.h"
#include "scenes/CullingSpec.h"

namespace cdb {

class CullideWithHierarchy final : public CullingStrategy {
 public:
  explicit CullideWithHierarchy(const DetectorOptions& options,
                                CullideWithHierarchyOptions config = {});

  [[nodiscard]] std::string_view name() const override { return "cullide_bvh"; }
  void attach(const SceneGeometry& scene, VisibilityBackend& backend) override;
  [[nodiscard]] CullingResult cull(const FrameInput& frame) override;

 private:
  // The two passes along one axis over the objects' active nodes; prunes nodes and objects.
  void pruneAlong(std::vector<ObjectId>& objects, int axis, std::span<const Pose> poses);

  DetectorOptions options_;
  CullideWithHierarchyOptions config_;
  const SceneGeometry* scene_ = nullptr;
  VisibilityBackend* backend_ = nullptr;
  SceneHierarchies hierarchies_;
  NodeFrontier frontier_;
  std::vector<std::uint8_t> visible_;    // query answers, reused across frames
  PassQueries queries_;                  // where each object's answers begin, in each pass
  GrowOnlyArray<OrientedBox> boxes_;     // the objects' node boxes along one axis, in turn
  std::vector<std::size_t> boxesStart_;  // where each object's begin in boxes_, and the end
  std::vector<std::uint8_t> keep_;       // per active node of one object
};

}  // namespace cdb
