#pragma once
// An oriented bounding box in some frame: centre, orthonormal axes (columns), half extents.
#include <Eigen/Geometry>

#include "core/Pose.h"

namespace cdb {

struct OrientedBox {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  // columns are the box axes
  Eigen::Vector3d halfExtents = Eigen::Vector3d::Zero();

  [[nodiscard]] double volume() const { return 8.0 * halfExtents.prod(); }
  [[nodiscard]] OrientedBox transformed(const Pose& pose) const {
    return {pose.apply(center), pose.rotation.toRotationMatrix() * axes, halfExtents};
  }
  [[nodiscard]] Eigen::Vector3d corner(int i) const {
    const Eigen::Vector3d s((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
    return center + axes * s.cwiseProduct(halfExtents);
  }
};

}  // namespace cdb
