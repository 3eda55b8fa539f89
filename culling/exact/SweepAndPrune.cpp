#include "culling/exact/SweepAndPrune.h"

#include <algorithm>
#include <cmath>

namespace cdb {

namespace {

// Grid sizing: cells about this many average boxes wide, at most this many per axis; a box over
// more cells than kMaxCellsPerBox is swept against the whole other input instead.
constexpr double kCellWidthInBoxes = 8.0;
constexpr int kMaxCellsPerAxis = 64;
constexpr int kMaxCellsPerBox = 27;
// Below this many boxes on either side one sweep is cheap enough.
constexpr std::size_t kGridMinimum = 64;

// False for empty boxes and for any NaN bound, which would also break the sort's ordering.
bool isSweepable(const Aabb& box) { return (box.min().array() <= box.max().array()).all(); }

// Without short-circuits: the four comparisons are unpredictable, their conjunction rarely true.
template <class Entry>
bool overlapOffAxis(const Entry& a, const Entry& b) {
  return (a.lo[1] <= b.hi[1]) & (b.lo[1] <= a.hi[1]) & (a.lo[2] <= b.hi[2]) & (b.lo[2] <= a.hi[2]);
}

// The axis along which the centres spread most, so that intervals on it overlap least.
int sweepAxis(std::span<const Aabb> a, std::span<const Aabb> b) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), sumSquares = Eigen::Vector3d::Zero();
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();  // first centre, against cancellation
  bool shifted = false;
  double count = 0;
  for (auto boxes : {a, b}) {
    for (const Aabb& box : boxes) {
      if (!isSweepable(box)) continue;
      const Eigen::Vector3d centre = 0.5 * box.min() + 0.5 * box.max();
      if (!shifted) shift = centre, shifted = true;
      const Eigen::Vector3d d = centre - shift;
      sum += d;
      sumSquares += d.cwiseProduct(d);
      count += 1;
    }
  }
  if (count < 2) return 0;
  const Eigen::Vector3d variance = sumSquares / count - (sum / count).cwiseAbs2();
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (variance[k] > variance[axis]) axis = k;
  return axis;
}

template <class Entry>
void fillEntries(std::span<const Aabb> boxes, int axis, std::vector<Entry>& entries) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  entries.clear();
  for (std::uint32_t i = 0; i < boxes.size(); ++i) {
    const Aabb& b = boxes[i];
    if (!isSweepable(b)) continue;
    entries.push_back(
        {{b.min()[axis], b.min()[u], b.min()[v]}, {b.max()[axis], b.max()[u], b.max()[v]}, i, 0});
  }
}

// Both ranges sorted on lo[0]. Merges them; the box that starts first meets every box of the other
// range that starts inside it and has not been swept yet, so each overlapping pair is met once.
template <class Entry, class Emit>
void sweepSorted(std::span<const Entry> a, std::span<const Entry> b, Emit&& emit) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (a[i].lo[0] <= b[j].lo[0]) {
      const Entry& e = a[i++];
      for (std::size_t m = j; m < b.size() && b[m].lo[0] <= e.hi[0]; ++m)
        if (overlapOffAxis(e, b[m])) emit(e, b[m]);
    } else {
      const Entry& e = b[j++];
      for (std::size_t m = i; m < a.size() && a[m].lo[0] <= e.hi[0]; ++m)
        if (overlapOffAxis(e, a[m])) emit(a[m], e);
    }
  }
}

// A uniform grid over the region where boxes of both inputs can meet (in the reordered axes).
struct Grid {
  double origin[3] = {0, 0, 0};
  double inverseSize[3] = {0, 0, 0};
  int cells[3] = {1, 1, 1};

  // Monotone in x, so a box's cells along an axis are those of its two bounds and everything
  // between; clamping keeps coordinates beyond the region in the border cells.
  [[nodiscard]] int cellOf(double x, int k) const {
    const double t =
        std::min(std::max((x - origin[k]) * inverseSize[k], 0.0), double(cells[k] - 1));
    return int(t);
  }
  [[nodiscard]] std::uint32_t id(int c0, int c1, int c2) const {
    return std::uint32_t((c0 * cells[1] + c1) * cells[2] + c2);
  }
  [[nodiscard]] int total() const { return cells[0] * cells[1] * cells[2]; }
};

// The grid for two inputs, or one cell when a single sweep is the better choice.
template <class Entry>
Grid fitGrid(const std::vector<Entry>& a, const std::vector<Entry>& b, double (&lo)[3],
             double (&hi)[3]) {
  Grid grid;
  if (std::min(a.size(), b.size()) < kGridMinimum) return grid;
  double extentSum = 0;
  for (const auto* entries : {&a, &b})
    for (const Entry& e : *entries)
      extentSum += std::max({e.hi[0] - e.lo[0], e.hi[1] - e.lo[1], e.hi[2] - e.lo[2]});
  const double cellWidth = kCellWidthInBoxes * extentSum / double(a.size() + b.size());
  if (!(cellWidth > 0) || !std::isfinite(cellWidth)) return grid;
  Grid fitted;
  for (int k = 0; k < 3; ++k) {
    const double extent = hi[k] - lo[k];
    if (!std::isfinite(extent)) return grid;
    fitted.cells[k] = int(std::clamp(std::ceil(extent / cellWidth), 1.0, double(kMaxCellsPerAxis)));
    fitted.origin[k] = lo[k];
    fitted.inverseSize[k] = extent > 0 ? fitted.cells[k] / extent : 0.0;
  }
  return fitted.total() > 1 ? fitted : grid;
}

// Copies each entry into every cell it covers, or into `large` when it covers too many. Entries
// outside the region meet nothing of the other input and are dropped.
template <class Entry>
void bin(const std::vector<Entry>& entries, const Grid& grid, const double (&lo)[3],
         const double (&hi)[3], std::vector<Entry>& binned, std::vector<Entry>& large) {
  binned.clear();
  large.clear();
  for (const Entry& e : entries) {
    bool inside = true;
    for (int k = 0; k < 3; ++k) inside &= e.lo[k] <= hi[k] && lo[k] <= e.hi[k];
    if (!inside) continue;
    int first[3], last[3];
    for (int k = 0; k < 3; ++k)
      first[k] = grid.cellOf(e.lo[k], k), last[k] = grid.cellOf(e.hi[k], k);
    const int covered =
        (last[0] - first[0] + 1) * (last[1] - first[1] + 1) * (last[2] - first[2] + 1);
    if (covered > kMaxCellsPerBox) {
      large.push_back(e);
      continue;
    }
    for (int c0 = first[0]; c0 <= last[0]; ++c0)
      for (int c1 = first[1]; c1 <= last[1]; ++c1)
        for (int c2 = first[2]; c2 <= last[2]; ++c2) {
          binned.push_back(e);
          binned.back().cell = grid.id(c0, c1, c2);
        }
  }
}

}  // namespace

// Sorts small keys and moves each entry once, rather than swapping whole entries.
void SweepAndPrune::sortOnSweepAxis(std::vector<Entry>& entries) {
  keys_.resize(entries.size());
  for (std::uint32_t i = 0; i < entries.size(); ++i) keys_[i] = {entries[i].lo[0], i};
  std::sort(keys_.begin(), keys_.end(),
            [](const SortKey& x, const SortKey& y) { return x.lo < y.lo; });
  scratch_.resize(entries.size());
  for (std::size_t i = 0; i < keys_.size(); ++i) scratch_[i] = entries[keys_[i].position];
  entries.swap(scratch_);
}

// Stable counting sort on the cell: entries already in sweep order stay so within each cell.
void SweepAndPrune::sortByCell(std::vector<Entry>& entries, std::uint32_t cells) {
  cellStarts_.assign(cells + 1, 0);
  for (const Entry& e : entries) ++cellStarts_[e.cell + 1];
  for (std::uint32_t c = 0; c < cells; ++c) cellStarts_[c + 1] += cellStarts_[c];
  scratch_.resize(entries.size());
  for (const Entry& e : entries) scratch_[cellStarts_[e.cell]++] = e;
  entries.swap(scratch_);
}

void SweepAndPrune::overlaps(std::span<const Aabb> boxes, std::vector<IndexPair>& out) {
  out.clear();
  auto& entries = entries_[0];
  fillEntries(boxes, sweepAxis(boxes, {}), entries);
  sortOnSweepAxis(entries);
  const std::size_t n = entries.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Entry& e = entries[k];
    for (std::size_t m = k + 1; m < n && entries[m].lo[0] <= e.hi[0]; ++m) {
      if (overlapOffAxis(e, entries[m])) {
        const std::uint32_t other = entries[m].index;
        out.push_back({std::min(e.index, other), std::max(e.index, other)});
      }
    }
  }
  std::sort(out.begin(), out.end());
}

void SweepAndPrune::overlaps(std::span<const Aabb> a, std::span<const Aabb> b,
                             std::vector<IndexPair>& out) {
  out.clear();
  const int axis = sweepAxis(a, b);
  fillEntries(a, axis, entries_[0]);
  fillEntries(b, axis, entries_[1]);
  if (entries_[0].empty() || entries_[1].empty()) return;

  // Where boxes of both inputs can meet.
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k) {
    double loA = entries_[0][0].lo[k], hiA = entries_[0][0].hi[k];
    for (const Entry& e : entries_[0]) loA = std::min(loA, e.lo[k]), hiA = std::max(hiA, e.hi[k]);
    double loB = entries_[1][0].lo[k], hiB = entries_[1][0].hi[k];
    for (const Entry& e : entries_[1]) loB = std::min(loB, e.lo[k]), hiB = std::max(hiB, e.hi[k]);
    lo[k] = std::max(loA, loB);
    hi[k] = std::min(hiA, hiB);
    if (lo[k] > hi[k]) return;
  }

  const auto emit = [&](const Entry& x, const Entry& y) { out.push_back({x.index, y.index}); };
  sortOnSweepAxis(entries_[0]);
  sortOnSweepAxis(entries_[1]);
  const Grid grid = fitGrid(entries_[0], entries_[1], lo, hi);
  if (grid.total() == 1) {
    sweepSorted<Entry>(entries_[0], entries_[1], emit);
    return;
  }

  for (int side = 0; side < 2; ++side) {
    bin(entries_[side], grid, lo, hi, binned_[side], large_[side]);
    sortByCell(binned_[side], std::uint32_t(grid.total()));
  }
  // Cell by cell; a pair is reported only by the cell holding the lower corner of the two boxes'
  // intersection, which both boxes cover, so exactly once.
  const auto& binnedA = binned_[0];
  const auto& binnedB = binned_[1];
  std::size_t i = 0, j = 0;
  while (i < binnedA.size() && j < binnedB.size()) {
    const std::uint32_t cell = std::max(binnedA[i].cell, binnedB[j].cell);
    while (i < binnedA.size() && binnedA[i].cell < cell) ++i;
    while (j < binnedB.size() && binnedB[j].cell < cell) ++j;
    std::size_t iEnd = i, jEnd = j;
    while (iEnd < binnedA.size() && binnedA[iEnd].cell == cell) ++iEnd;
    while (jEnd < binnedB.size() && binnedB[jEnd].cell == cell) ++jEnd;
    if (iEnd > i && jEnd > j) {
      sweepSorted<Entry>(std::span(binnedA).subspan(i, iEnd - i),
                         std::span(binnedB).subspan(j, jEnd - j),
                         [&](const Entry& x, const Entry& y) {
                           const int c0 = grid.cellOf(std::max(x.lo[0], y.lo[0]), 0);
                           const int c1 = grid.cellOf(std::max(x.lo[1], y.lo[1]), 1);
                           const int c2 = grid.cellOf(std::max(x.lo[2], y.lo[2]), 2);
                           if (grid.id(c0, c1, c2) == cell) emit(x, y);
                         });
    }
    i = iEnd;
    j = jEnd;
  }

  // Boxes too large for the grid, against every box of the other input (both still in sweep
  // order); pairs of two large boxes come from the first of these sweeps only.
  if (!large_[0].empty()) sweepSorted<Entry>(large_[0], entries_[1], emit);
  if (large_[1].empty()) return;
  auto& smallA = scratch_;
  smallA.clear();
  std::size_t next = 0;  // large_[0] is a subsequence of entries_[0]
  for (const Entry& e : entries_[0]) {
    if (next < large_[0].size() && large_[0][next].index == e.index) {
      ++next;
      continue;
    }
    smallA.push_back(e);
  }
  sweepSorted<Entry>(smallA, large_[1], emit);
}

std::vector<IndexPair> sweepAndPrune(std::span<const Aabb> boxes) {
  SweepAndPrune sap;
  std::vector<IndexPair> out;
  sap.overlaps(boxes, out);
  return out;
}

}  // namespace cdb
