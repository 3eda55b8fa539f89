#pragma once
// Collision-independent sets along one view direction (thesis 3.3, Algorithm 3.2), object level:
// the potentially colliding objects are partitioned into sets such that no two objects of
// different sets can collide. CisConstruction holds the algorithm's decisions and why the
// partition is safe; this draws whole objects for it.
#include <array>
#include <cstdint>
#include <vector>

#include "culling/CisConstruction.h"
#include "culling/CullingStrategy.h"
#include "culling/SortedIntervals.h"
#include "culling/DetectorRegistry.h"
#include "culling/WorldBounds.h"
#include "scenes/CullingSpec.h"

namespace cdb {

class CollisionIndependentSets final : public CullingStrategy {
 public:
  explicit CollisionIndependentSets(const DetectorOptions& options, CisOptions cis = {});

  [[nodiscard]] std::string_view name() const override { return "cis"; }
  void attach(const SceneGeometry& scene, VisibilityBackend& backend) override;
  [[nodiscard]] CullingResult cull(const FrameInput& frame) override;

  // What the last frame did, beyond CullingCounters.
  struct FrameStats {
    int axis = 0;
    std::uint64_t sortExchanges = 0;
    // Fully visible in pass 1 and left out of every set in pass 2.
    std::uint64_t dropped = 0;
    // Sets that ended with one member (nothing to collide with), not output.
    std::uint64_t singletons = 0;
    // Per set built in pass 1, in order: its separating surface SS, as a position in the
    // far-to-near element order (the near end of its nearest pass-1 member).
    std::vector<std::uint32_t> separatingSurfaces;
  };
  [[nodiscard]] const FrameStats& lastFrame() const { return stats_; }

 private:
  DetectorOptions options_;
  CisOptions config_;
  const SceneGeometry* scene_ = nullptr;
  VisibilityBackend* backend_ = nullptr;
  WorldBounds bounds_;
  std::vector<ObjectId> allObjects_;
  std::array<SortedIntervals, 3> sorted_;  // one list per axis, kept across frames
  FrameStats stats_;
  CisConstruction cis_;
  std::vector<std::uint8_t> visible_;  // query answers, reused across frames
  std::vector<std::uint8_t> bySlot_;   // the same per slot of the sorted list
};

}  // namespace cdb
