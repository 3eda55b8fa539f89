#pragma once
// Collision filtering with depth order (thesis 3.2, Algorithm 3.1): CULLIDE's two-pass pruning
// with the objects drawn in depth order. Along a view axis, pass 1 looks along +axis and draws
// objects far to near (decreasing Min of their projected AABB); pass 2 looks along -axis and
// draws them in the reverse order, which is again far to near for that view. Both passes share
// one depth clear. An object is tested in pass 1 against every object of larger Min and in pass 2
// against every object of smaller Min, i.e. against all others, so CULLIDE's argument holds: fully
// visible in both passes means it touches no other object. Objects whose boxes are apart along the
// view are each in front of everything drawn before them, so they are pruned even where their
// images overlap, which CULLIDE's fixed order cannot do (Figure 3.2).
// Object level along x, y, z, then triangle level on the objects left; one set comes out.
#include <array>
#include <cstdint>
#include <vector>

#include "culling/CullingStrategy.h"
#include "culling/SortedIntervals.h"
#include "culling/DetectorRegistry.h"
#include "culling/TwoPassPruning.h"
#include "culling/WorldBounds.h"

namespace cdb {

class DepthSortedCulling final : public CullingStrategy {
 public:
  explicit DepthSortedCulling(const DetectorOptions& options);

  [[nodiscard]] std::string_view name() const override { return "sorted"; }
  void attach(const SceneGeometry& scene, VisibilityBackend& backend) override;
  [[nodiscard]] CullingResult cull(const FrameInput& frame) override;

  // Exchanges made by the last frame's insertion sorts, all three axes together (0 on the frame
  // that built the lists).
  [[nodiscard]] std::uint64_t lastSortExchanges() const { return exchanges_; }

 private:
  // Objects flagged in inSet_, in decreasing Min along `axis`: far to near looking along +axis.
  void farToNear(int axis, std::vector<ObjectId>& order) const;
  void pruneObjects(std::vector<ObjectId>& pcs, int axis);
  void pruneTriangles(std::vector<SetMember>& members, int axis);
  [[nodiscard]] ViewSpec viewAlong(int axis, const Aabb& bounds) const;

  DetectorOptions options_;
  const SceneGeometry* scene_ = nullptr;
  VisibilityBackend* backend_ = nullptr;
  WorldBounds bounds_;
  std::vector<ObjectId> allObjects_;
  std::array<SortedIntervals, 3> sorted_;  // one list per axis, kept across frames
  std::uint64_t exchanges_ = 0;
  std::vector<std::uint8_t> inSet_;    // per object: still in the set being pruned
  TwoPassAnswers visible_;  // query answers, reused across frames
};

}  // namespace cdb
