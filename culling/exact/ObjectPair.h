#pragma once
#include <compare>
#include <vector>

#include "scenes/SceneGeometry.h"

namespace cdb {

// An unordered object pair, stored with a < b.
struct ObjectPair {
  ObjectId a = 0;
  ObjectId b = 0;
  static ObjectPair of(ObjectId x, ObjectId y) { return x < y ? ObjectPair{x, y} : ObjectPair{y, x}; }
  auto operator<=>(const ObjectPair&) const = default;
};

// Colliding pairs, sorted and unique, plus the work it took to find them.
struct CollisionReport {
  std::vector<ObjectPair> collidingPairs;
  std::uint64_t pairsTested = 0;             // object pairs whose triangles were tested
  std::uint64_t triangleTests = 0;           // triangle-triangle tests run
  std::uint64_t collidingTrianglePairs = 0;  // of which intersecting
};

}  // namespace cdb
