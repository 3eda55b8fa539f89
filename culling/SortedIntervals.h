#pragma once
// The sorted list of interval endpoints along a view direction (thesis 3.2): each object's world
// AABB projected on the direction gives [Min, Max]; the 2n endpoints are kept sorted across
// frames and re-sorted by insertion sort, which under slow motion costs O(n + exchanges)
// (temporal coherence, [CLMP95]).
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "culling/WorldBounds.h"
#include "scenes/SceneGeometry.h"

namespace cdb {

class SortedIntervals {
 public:
  struct Endpoint {
    ObjectId object = 0;
    std::uint32_t slot = 0;  // index of the object in the list given to update()
    bool isMax = false;
    double value = 0.0;
  };

  // Projects the boxes of `objects` on `direction` and re-sorts. When `objects` is the same
  // sequence as in the previous call, last frame's order is the starting point (insertion sort);
  // otherwise the list is rebuilt from scratch. Returns the number of exchanges.
  std::uint64_t update(std::span<const ObjectId> objects, const WorldBounds& bounds,
                       const Eigen::Vector3d& direction);
  // The same with the intervals given: intervals[slot] is [Min, Max] of objects[slot] along the
  // direction (for geometry other than whole objects, e.g. the active nodes of a hierarchy).
  std::uint64_t update(std::span<const ObjectId> objects,
                       std::span<const std::pair<double, double>> intervals);

  // Ascending along the direction: for a view looking along it, near to far. At equal values a
  // MIN comes before a MAX, so touching intervals count as overlapping.
  [[nodiscard]] std::span<const Endpoint> endpoints() const { return list_; }
  // Position in endpoints() of the MIN / MAX endpoint of the object at `slot`.
  [[nodiscard]] std::uint32_t minIndex(std::uint32_t slot) const { return minIndex_[slot]; }
  [[nodiscard]] std::uint32_t maxIndex(std::uint32_t slot) const { return maxIndex_[slot]; }
  [[nodiscard]] std::size_t objectCount() const { return objects_.size(); }
  [[nodiscard]] bool lastUpdateRebuilt() const { return rebuilt_; }

  // Strict total order of the list; exposed for tests.
  [[nodiscard]] static bool before(const Endpoint& a, const Endpoint& b);

 private:
  void rebuild(std::span<const ObjectId> objects);
  std::uint64_t resort();
  std::uint64_t insertionSort();
  void indexPositions();

  std::vector<ObjectId> objects_;
  std::vector<Endpoint> list_;
  std::vector<std::uint32_t> minIndex_;
  std::vector<std::uint32_t> maxIndex_;
  bool rebuilt_ = false;
};

// [min, max] of a box projected on a direction.
[[nodiscard]] std::pair<double, double> projectAabb(const Aabb& box, const Eigen::Vector3d& d);

}  // namespace cdb
