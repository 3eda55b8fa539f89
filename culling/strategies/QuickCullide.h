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
#include "culling/DetectorRegistry.h"
#include "culling/TwoPassPruning.h"
#include "culling/WorldBounds.h"

namespace cdb {

class QuickCullide final : public CullingStrategy {
 public:
  explicit QuickCullide(const DetectorOptions& options);

  [[nodiscard]] std::string_view name() const override { return "quick_cullide"; }
  void attach(const SceneGeometry& scene, VisibilityBackend& backend) override;
  [[nodiscard]] CullingResult cull(const FrameInput& frame) override;

 private:
  // Triangles of one side of a pair: every triangle of the mesh, or the listed ones (ascending).
  struct Side {
    bool all = true;
    std::vector<std::uint32_t> triangles;
  };
  // A member at triangle level. Which of its triangles may meet a partner depends only on whether
  // the partner comes later in pass-1 order (pass 2 clears them) or earlier (pass 1 clears them).
  struct Member {
    ObjectId object = 0;
    Side towardLater;    // its side in pairs with later members
    Side towardEarlier;  // its side in pairs with earlier members
  };

  void classifyObjects(const Eigen::Vector3d& axis, bool firstAxis);
  void classifyTriangles(const Eigen::Vector3d& axis);
  // Drops the pairs with an empty side, then the members left in no pair.
  void dropEmptyPairsAndMembers();
  // Each member's triangles to draw: the sides it has in its pairs (no list where a side has
  // every triangle).
  [[nodiscard]] std::vector<SetMember> drawnTriangles() const;
  [[nodiscard]] CullingResult result(const VisibilityCounters& work) const;

  DetectorOptions options_;
  const SceneGeometry* scene_ = nullptr;
  VisibilityBackend* backend_ = nullptr;
  WorldBounds bounds_;
  TwoPassAnswers answers_;  // reused across passes and frames

  // Object level: the objects still in some pair (ascending ids = pass-1 order) and the pairs.
  std::vector<ObjectId> objects_;
  std::vector<ObjectPair> objectPairs_;
  std::vector<std::uint32_t> positionOf_;  // per object id: its position in objects_

  // Triangle level: the members (pass-1 order) and their pairs (indices, earlier member first).
  std::vector<Member> members_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> memberPairs_;
  std::vector<std::uint8_t> isEarlier_, isLater_;  // per member: earlier / later one of some pair
};

}  // namespace cdb
