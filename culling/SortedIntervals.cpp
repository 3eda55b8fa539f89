#include "culling/SortedIntervals.h"

#include <algorithm>
#include <utility>

namespace cdb {

std::pair<double, double> projectAabb(const Aabb& box, const Eigen::Vector3d& d) {
  double lo = 0.0;
  double hi = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double a = d[k] * box.min()[k];
    const double b = d[k] * box.max()[k];
    lo += std::min(a, b);
    hi += std::max(a, b);
  }
  return {lo, hi};
}

bool SortedIntervals::before(const Endpoint& a, const Endpoint& b) {
  if (a.value != b.value) return a.value < b.value;
  if (a.isMax != b.isMax) return !a.isMax;
  return a.object < b.object;
}

void SortedIntervals::rebuild(std::span<const ObjectId> objects) {
  objects_.assign(objects.begin(), objects.end());
  list_.clear();
  list_.reserve(2 * objects_.size());
  for (std::uint32_t s = 0; s < objects_.size(); ++s) {
    list_.push_back({objects_[s], s, false, 0.0});
    list_.push_back({objects_[s], s, true, 0.0});
  }
}

std::uint64_t SortedIntervals::insertionSort() {
  std::uint64_t exchanges = 0;
  for (std::size_t i = 1; i < list_.size(); ++i) {
    const Endpoint e = list_[i];
    std::size_t j = i;
    for (; j > 0 && before(e, list_[j - 1]); --j) list_[j] = list_[j - 1];
    exchanges += i - j;
    list_[j] = e;
  }
  return exchanges;
}

void SortedIntervals::indexPositions() {
  minIndex_.resize(objects_.size());
  maxIndex_.resize(objects_.size());
  for (std::uint32_t i = 0; i < list_.size(); ++i)
    (list_[i].isMax ? maxIndex_ : minIndex_)[list_[i].slot] = i;
}

std::uint64_t SortedIntervals::update(std::span<const ObjectId> objects, const WorldBounds& bounds,
                                      const Eigen::Vector3d& direction) {
  rebuilt_ = !std::ranges::equal(objects, objects_);
  if (rebuilt_) rebuild(objects);
  for (auto& e : list_) {
    const auto [lo, hi] = projectAabb(bounds[e.object], direction);
    e.value = e.isMax ? hi : lo;
  }
  return resort();
}

std::uint64_t SortedIntervals::update(std::span<const ObjectId> objects,
                                      std::span<const std::pair<double, double>> intervals) {
  rebuilt_ = !std::ranges::equal(objects, objects_);
  if (rebuilt_) rebuild(objects);
  for (auto& e : list_) e.value = e.isMax ? intervals[e.slot].second : intervals[e.slot].first;
  return resort();
}

std::uint64_t SortedIntervals::resort() {
  std::uint64_t exchanges = 0;
  if (rebuilt_)
    std::sort(list_.begin(), list_.end(), before);  // no previous order to be coherent with
  else
    exchanges = insertionSort();
  indexPositions();
  return exchanges;
}

}  // namespace cdb
