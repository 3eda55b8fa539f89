#pragma once
// Quick-CULLIDE (Govindaraju, Lin, Manocha, IEEE VR 2005; thesis 2.4): CULLIDE's passes (object
// then triangle level, pass 1 in order, pass 2 in reverse, along x, y and z) with each pass'
// answers kept to classify pairs instead of being collapsed into one PCS. By CULLIDE's lemma, with
// P1..Pn the pass-1 order, a pair Pi, Pj (i < j) can only collide when Pj was not fully visible in
// pass 1 and Pi not fully visible in pass 2: the pieces fully visible in pass 1 only form a
// collision-free subset, likewise those of pass 2 only. A pair is free as soon as one axis proves
// it. What is left goes to the exact phase as one set that lists its pairs, each side restricted
// to the triangles that may still meet the other side.
#include <cstdint>
#include <vector>

#include "culling/CullingStrategy.h"
#include "culling/StrategyRegistry.h"
#include "culling/TwoPassPruning.h"
#include "culling/WorldBounds.h"

namespace cdb {

class QuickCullide final : public CullingStrategy {
 public:
  explicit QuickCullide(const StrategyOptions& options);

  [[nodiscard]] std::string_view name() const override { return "quick_cullide"; }
  void attach(const SceneGeometry& scene, VisibilityBackend& backend) override;
  [[nodiscard]] CullingResult cull(const FrameInput& frame) override;

 private:
  // Triangles of one side of a pair: every triangle of the mesh, or the listed ones (ascending).
  struct Side {
    bool all = true;
    std::vector<std::uint32_t> triangles;
  };
  // A pair of members at triangle level; `first` comes before `second` in pass-1 order.
  struct TrianglePair {
    std::uint32_t first = 0;
    std::uint32_t second = 0;
    Side firstSide, secondSide;
  };

  void classifyObjects(const Eigen::Vector3d& axis, bool firstAxis);
  void classifyTriangles(const Eigen::Vector3d& axis);
  // Members with no pair left are dropped; pairs renumbered.
  void dropUnpairedMembers();
  // Each member's triangles: the union of its sides over its pairs (explicit lists).
  [[nodiscard]] std::vector<SetMember> drawnTriangles() const;
  [[nodiscard]] CullingResult result(const VisibilityCounters& work) const;

  StrategyOptions options_;
  const SceneGeometry* scene_ = nullptr;
  VisibilityBackend* backend_ = nullptr;
  WorldBounds bounds_;
  TwoPassAnswers answers_;  // reused across passes and frames

  // Object level: the objects still in some pair (ascending ids = pass-1 order) and the pairs.
  std::vector<ObjectId> objects_;
  std::vector<ObjectPair> objectPairs_;
  std::vector<std::uint32_t> positionOf_;  // per object id: its position in objects_

  // Triangle level: the members (pass-1 order) and their pairs.
  std::vector<ObjectId> members_;
  std::vector<TrianglePair> trianglePairs_;
  // Per member, per mesh triangle: bit 0 fully visible in pass 1, bit 1 in pass 2 (last axis).
  std::vector<std::uint8_t> triangleAnswers_;
  std::vector<std::size_t> answersBase_;
};

}  // namespace cdb
