#pragma once
// What the geometric oracles share: a queried box is fully visible iff, for every piece written
// earlier in the pass whose box overlaps it in the image plane, it lies entirely in front (strictly
// nearer along the view). Views must be along an axis. Boxes that touch are never fully visible
// with respect to each other, as with the conservative backends.
#include <gtest/gtest.h>

#include <cmath>
#include <span>

#include "core/Aabb.h"
#include "culling/SortedIntervals.h"
#include "culling/visibility/ScriptedVisibilityOracle.h"

namespace cdb::testing {

// The view direction of the pass the oracle's log is in.
inline Eigen::Vector3d currentViewDirection(const ScriptedVisibilityOracle& oracle) {
  const auto& log = oracle.log();
  for (auto it = log.rbegin(); it != log.rend(); ++it)
    if (it->kind == VisibilityCall::Kind::BeginPass) return it->view.direction;
  ADD_FAILURE() << "query outside a pass";
  return Eigen::Vector3d::UnitZ();
}

// Whether `query` is fully visible against `written` in the oracle's current pass; `boxOf` gives
// the world box of a written call and is asked only until the first occluder.
template <class BoxOf>
bool fullyVisibleAlongAxis(const ScriptedVisibilityOracle& oracle, const Aabb& query,
                           std::span<const VisibilityCall> written, BoxOf&& boxOf) {
  const Eigen::Vector3d d = currentViewDirection(oracle);
  int axis = 0;
  d.cwiseAbs().maxCoeff(&axis);
  EXPECT_DOUBLE_EQ(std::abs(d[axis]), 1.0) << "views must be along an axis";
  const double queryFar = projectAabb(query, d).second;
  for (const VisibilityCall& w : written) {
    const Aabb wb = boxOf(w);
    bool imageOverlap = true;
    for (int k = 0; k < 3; ++k)
      if (k != axis && (query.min()[k] > wb.max()[k] || wb.min()[k] > query.max()[k]))
        imageOverlap = false;
    if (imageOverlap && !(queryFar < projectAabb(wb, d).first)) return false;
  }
  return true;
}

}  // namespace cdb::testing
