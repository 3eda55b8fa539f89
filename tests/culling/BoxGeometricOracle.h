#pragma once
// A scripted oracle for strategies that draw bounding boxes (queryBox / writeBox): each box
// stands for its world AABB under the object's pose, decided as AxisViewOcclusion.h says.
#include <gtest/gtest.h>

#include <span>

#include "AxisViewOcclusion.h"
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
  bool decide(const VisibilityCall& q, std::span<const VisibilityCall> written) const {
    EXPECT_EQ(q.kind, VisibilityCall::Kind::QueryBox) << "this oracle decides boxes only";
    return fullyVisibleAlongAxis(oracle_, worldBox(q.object, q.box), written,
                                 [&](const VisibilityCall& w) {
                                   EXPECT_EQ(w.kind, VisibilityCall::Kind::WriteBox)
                                       << "this oracle decides boxes only";
                                   EXPECT_NE(w.object, q.object)
                                       << "an object's node queried after one of its own was written";
                                   return worldBox(w.object, w.box);
                                 });
  }

  ScriptedVisibilityOracle oracle_;
};

}  // namespace cdb::testing
