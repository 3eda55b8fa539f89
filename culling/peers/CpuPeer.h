#pragma once
// A CPU collision library as a detector by itself: it decides the colliding pairs on the CPU, with
// its own broad and narrow phases, and asks no visibility backend. Each peer says which pairs its
// library reported, in the library's order and possibly repeated; detect() times that and turns
// it into the harness' answer (sorted, unique). The peers run no triangle tests of the project, so
// only pairsTested (pairs the library's narrow phase examined) is counted.
#include <cstdint>
#include <span>
#include <vector>

#include "core/Pose.h"
#include "culling/CollisionDetector.h"
#include "culling/exact/ObjectPair.h"

namespace cdb {

class CpuPeer : public CollisionDetector {
 public:
  [[nodiscard]] DetectedFrame detect(const FrameInput& frame) final;

 protected:
  struct LibraryPairs {
    std::vector<ObjectPair> pairs;  // the library's order, possibly repeated
    std::uint64_t pairsTested = 0;
  };
  [[nodiscard]] virtual LibraryPairs collide(std::span<const Pose> poses) = 0;
};

}  // namespace cdb
