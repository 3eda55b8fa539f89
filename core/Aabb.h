#pragma once
// Axis-aligned boxes are Eigen's AlignedBox; helpers for the transforms the project needs.
#include <Eigen/Geometry>

#include "core/Pose.h"

namespace cdb {

using Aabb = Eigen::AlignedBox3d;

// World box of a local box under a rigid pose (exact for the box, conservative for its content).
[[nodiscard]] inline Aabb transformAabb(const Aabb& local, const Pose& pose) {
  if (local.isEmpty()) return local;
  const Eigen::Matrix3d r = pose.rotation.toRotationMatrix();
  const Eigen::Vector3d c = pose.apply(local.center());
  const Eigen::Vector3d h = r.cwiseAbs() * (local.sizes() * 0.5);
  return Aabb(c - h, c + h);
}

}  // namespace cdb
