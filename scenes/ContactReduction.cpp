#include "scenes/ContactReduction.h"

#include <algorithm>

namespace cdb {

namespace {

double squaredDistance(const dContactGeom& a, const dContactGeom& b) {
  const double dx = a.pos[0] - b.pos[0], dy = a.pos[1] - b.pos[1], dz = a.pos[2] - b.pos[2];
  return dx * dx + dy * dy + dz * dz;
}

}  // namespace

std::span<const std::size_t> ContactPicker::pick(std::span<const dContact> contacts, std::size_t found,
                                                 std::size_t keep) {
  found = std::min(found, contacts.size());
  chosen_.clear();
  if (found <= keep) {
    for (std::size_t i = 0; i < found; ++i) chosen_.push_back(i);
    return chosen_;
  }
  if (keep == 0) return chosen_;
  // Strict comparisons below: ties go to the lower index, so the choice never depends on anything
  // but the contacts themselves.
  std::size_t next = 0;
  for (std::size_t i = 1; i < found; ++i) {
    if (contacts[i].geom.depth > contacts[next].geom.depth) next = i;
  }
  distance_.assign(found, 0.0);
  for (std::size_t i = 0; i < found; ++i) distance_[i] = squaredDistance(contacts[i].geom, contacts[next].geom);
  chosen_.push_back(next);
  while (chosen_.size() < keep) {
    next = 0;
    for (std::size_t i = 1; i < found; ++i) {
      if (distance_[i] > distance_[next]) next = i;
    }
    if (distance_[next] == 0.0) break;  // all the rest coincide with contacts already kept
    chosen_.push_back(next);
    for (std::size_t i = 0; i < found; ++i) {
      distance_[i] = std::min(distance_[i], squaredDistance(contacts[i].geom, contacts[next].geom));
    }
  }
  return chosen_;
}

}  // namespace cdb
