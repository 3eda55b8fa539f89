#pragma once
// A rigid transform: world = rotation * local + translation.
#include <Eigen/Geometry>

namespace cdb {

struct Pose {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  [[nodiscard]] Eigen::Vector3d apply(const Eigen::Vector3d& local) const {
    return rotation * local + translation;
  }
  [[nodiscard]] Eigen::Matrix4d matrix() const {
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    m.topLeftCorner<3, 3>() = rotation.toRotationMatrix();
    m.topRightCorner<3, 1>() = translation;
    return m;
  }
  [[nodiscard]] bool isFinite() const {
    return rotation.coeffs().allFinite() && translation.allFinite();
  }
};

}  // namespace cdb
