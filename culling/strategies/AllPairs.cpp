#include "culling/strategies/AllPairs.h"

namespace cdb {

void AllPairs::attach(const SceneGeometry& scene, VisibilityBackend& /*backend*/) { scene_ = &scene; }

CullingResult AllPairs::cull(const FrameInput& /*frame*/) {
  CullingResult result;
  const std::size_t n = scene_->objectCount();
  if (n < 2) return result;  // an object alone collides with nothing
  PotentiallyCollidingSet all;
  all.members.reserve(n);
  for (ObjectId o = 0; o < n; ++o) {
    all.members.push_back({o, {}});
    result.counters.pcsTriangles += scene_->meshOf(o).triangleCount();
  }
  result.counters.pcsSize = n;
  result.counters.sets = 1;
  result.sets.push_back(std::move(all));
  return result;
}

}  // namespace cdb
