#pragma once
// A scripted oracle for strategies that draw bounding boxes (queryBox / writeBox): each box
// stands for its world AABB under the object's pose, and a queried box is fully visible iff, for
// every box written earlier in the pass whose AABB overlaps it in the image plane, it lies
// entirely in front (strictly nearer along the view). Views must be along an axis. Boxes that
// touch are never fully visible with respect to each other, as with the conservative GL backend.
#include <gtest/gtest.h>

#include <cmath>
#include <span>

#include "culling/SortedIntervals.h"
#include "culling/visibility/ScriptedVisibilityOracle.h"

namespace cdb::testing {

class BoxGeometricOracle {
 public:
  BoxGeometricOracle()
      : oracle_([this](const VisibilityCall& q, std::span<const VisibilityCall> written) {
          return decide(q, written);
        }) {}
  BoxGeometricOracle(const BoxGeometricOracle&) = delete;
  BoxGeometricOracle& operator=(const BoxGeometricOracle&) = delete;

  ScriptedVisibilityOracle& backend() { return oracle_; }

  Aabb worldBox(ObjectId object, const OrientedBox& local) const {
    const Pose& pose = oracle_.poses()[object];
    const OrientedBox w = local.transformed(pose);
    const Eigen::Vector3d h = w.axes.cwiseAbs() * w.halfExtents;
    return Aabb(w.center - h, w.center + h);
  }

 private:
  Eigen::Vector3d currentDirection() const {
    const auto& log = oracle_.log();
    for (auto it = log.rbegin(); it != log.rend(); ++it)
      if (it->kind == VisibilityCall::Kind::BeginPass) return it->view.direction;
    ADD_FAILURE() << "query outside a pass";
    return Eigen::Vector3d::UnitZ();
  }

  bool decide(const VisibilityCall& q, std::span<const VisibilityCall> written) const {
    EXPECT_EQ(q.kind, VisibilityCall::Kind::QueryBox) << "this oracle decides boxes only";
    const Eigen::Vector3d d = currentDirection();
    int axis = 0;
    d.cwiseAbs().maxCoeff(&axis);
    EXPECT_DOUBLE_EQ(std::abs(d[axis]), 1.0) << "views must be along an axis";
    const Aabb qb = worldBox(q.object, q.box);
    const double qFar = projectAabb(qb, d).second;
    for (const auto& w : written) {
      EXPECT_EQ(w.kind, VisibilityCall::Kind::WriteBox) << "this oracle decides boxes only";
      EXPECT_NE(w.object, q.object) << "an object's node queried after one of its own was written";
      const Aabb wb = worldBox(w.object, w.box);
      bool imageOverlap = true;
      for (int k = 0; k < 3; ++k)
        if (k != axis && (qb.min()[k] > wb.max()[k] || wb.min()[k] > qb.max()[k]))
          imageOverlap = false;
      if (imageOverlap && !(qFar < projectAabb(wb, d).first)) return false;
    }
    return true;
  }

  ScriptedVisibilityOracle oracle_;
};

}  // namespace cdb::testing
