#pragma once
// Sweep-and-prune (Baraff 1992; Cohen et al., I-COLLIDE 1995) over closed axis-aligned boxes,
// sorting on the axis along which the box centres vary most. Used by the exact phase for the
// members of a set and for the triangles of a member pair.
#include <compare>
#include <cstdint>
#include <span>
#include <vector>

#include "core/Aabb.h"

namespace cdb {

struct IndexPair {
  std::uint32_t i = 0;
  std::uint32_t j = 0;
  auto operator<=>(const IndexPair&) const = default;
};

// Holds the sort buffers so that repeated calls do not allocate once they have grown.
// Boxes are closed: boxes that only touch overlap. Empty boxes and boxes with NaN bounds overlap
// nothing.
class SweepAndPrune {
 public:
  // Every pair i < j of overlapping boxes, sorted, into `out` (cleared first).
  void overlaps(std::span<const Aabb> boxes, std::vector<IndexPair>& out);

  // Every pair (i, j) with a[i] overlapping b[j], in no particular order, into `out` (cleared
  // first). Large inputs are first spread over a uniform grid of cells a few boxes wide and swept
  // cell by cell, as one sweep over many boxes meets too many pairs that overlap on its axis only.
  void overlaps(std::span<const Aabb> a, std::span<const Aabb> b, std::vector<IndexPair>& out);

 private:
  // A box with its bounds reordered so that the sweep axis comes first, stored in sweep order so
  // that the scans read memory sequentially; `cell` is its grid cell when swept per cell.
  struct Entry {
    double lo[3];
    double hi[3];
    std::uint32_t index;
    std::uint32_t cell;
  };
  struct SortKey {
    double lo;
    std::uint32_t position;
  };

  void sortOnSweepAxis(std::vector<Entry>& entries);
  void sortByCell(std::vector<Entry>& entries, std::uint32_t cells);

  std::vector<Entry> entries_[2];  // the sweepable boxes of each input
  std::vector<Entry> binned_[2];   // one copy per grid cell a box covers
  std::vector<Entry> large_[2];    // boxes covering too many cells, swept against everything
  std::vector<Entry> scratch_;
  std::vector<SortKey> keys_;
  std::vector<std::uint32_t> cellStarts_;
};

// Convenience form of SweepAndPrune::overlaps for a single call.
[[nodiscard]] std::vector<IndexPair> sweepAndPrune(std::span<const Aabb> boxes);

}  // namespace cdb
