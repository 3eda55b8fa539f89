#pragma once
// World-space AABBs of every object for a frame, from each mesh's local box computed once.
#include <span>
#include <vector>

#include "core/Aabb.h"
#include "core/Pose.h"
#include "scenes/SceneGeometry.h"

namespace cdb {

class WorldBounds {
 public:
  void attach(const SceneGeometry& scene);
  void update(std::span<const Pose> poses);
  [[nodiscard]] const Aabb& operator[](ObjectId object) const { return world_[object]; }
  // Union of the boxes of `objects`.
  template <class Range>
  [[nodiscard]] Aabb unionOf(const Range& objects) const {
    Aabb box;
    for (ObjectId o : objects) box.extend(world_[o]);
    return box;
  }

 private:
  const SceneGeometry* scene_ = nullptr;
  std::vector<Aabb> local_;  // per mesh
  std::vector<Aabb> world_;  // per object
};

}  // namespace cdb
