#include "culling/exact/SweepAndPrune.h"

#include <algorithm>

namespace cdb {

namespace {

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
void fillSorted(std::span<const Aabb> boxes, int axis, std::vector<Entry>& entries) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  entries.clear();
  for (std::uint32_t i = 0; i < boxes.size(); ++i) {
    const Aabb& b = boxes[i];
    if (!isSweepable(b)) continue;
    entries.push_back({{b.min()[axis], b.min()[u], b.min()[v]}, {b.max()[axis], b.max()[u], b.max()[v]}, i});
  }
  std::sort(entries.begin(), entries.end(),
            [](const Entry& x, const Entry& y) { return x.lo[0] < y.lo[0]; });
}

}  // namespace

void SweepAndPrune::overlaps(std::span<const Aabb> boxes, std::vector<IndexPair>& out) {
  out.clear();
  fillSorted(boxes, sweepAxis(boxes, {}), first_);
  const std::size_t n = first_.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Entry& e = first_[k];
    for (std::size_t m = k + 1; m < n && first_[m].lo[0] <= e.hi[0]; ++m) {
      if (overlapOffAxis(e, first_[m])) {
        const std::uint32_t other = first_[m].index;
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
  fillSorted(a, axis, first_);
  fillSorted(b, axis, second_);
  // Merge both sorted lists; the box that starts first meets every box of the other list that
  // starts inside it and has not been swept yet, so each overlapping pair is met exactly once.
  const std::size_t na = first_.size(), nb = second_.size();
  std::size_t i = 0, j = 0;
  while (i < na && j < nb) {
    if (first_[i].lo[0] <= second_[j].lo[0]) {
      const Entry& e = first_[i++];
      for (std::size_t m = j; m < nb && second_[m].lo[0] <= e.hi[0]; ++m)
        if (overlapOffAxis(e, second_[m])) out.push_back({e.index, second_[m].index});
    } else {
      const Entry& e = second_[j++];
      for (std::size_t m = i; m < na && first_[m].lo[0] <= e.hi[0]; ++m)
        if (overlapOffAxis(e, first_[m])) out.push_back({first_[m].index, e.index});
    }
  }
}

std::vector<IndexPair> sweepAndPrune(std::span<const Aabb> boxes) {
  SweepAndPrune sap;
  std::vector<IndexPair> out;
  sap.overlaps(boxes, out);
  return out;
}

}  // namespace cdb
