#pragma once
// What a culling strategy hands to the exact phase: sets of objects (each possibly restricted to a
// subset of its triangles) such that no two objects of different sets, and no pruned object,
// can collide.
#include <cstdint>
#include <vector>

#include "scenes/SceneGeometry.h"

namespace cdb {

struct SetMember {
  ObjectId object = 0;
  // Local triangle indices that may still collide; empty means every triangle of the mesh.
  std::vector<std::uint32_t> triangles;
  bool allTriangles() const { return triangles.empty(); }
};

struct PotentiallyCollidingSet {
  std::vector<SetMember> members;
};

using PotentiallyCollidingSets = std::vector<PotentiallyCollidingSet>;

}  // namespace cdb
