#pragma once
// Initial poses and velocities of the bodies: explicit poses from the config, or seeded random
// placement (ScenarioConfig.h, RandomPlacement) by rejection sampling on bounding spheres.
#include <cstdint>
#include <random>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/Pose.h"
#include "scenes/MeshMeasures.h"
#include "scenes/ScenarioConfig.h"

namespace cdb {

struct BodyStart {
  Pose pose;  // maps mesh-local coordinates to world
  Eigen::Vector3d linearVelocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d angularVelocity = Eigen::Vector3d::Zero();  // rad/s, world frame
};

// Intrinsic rotations about X, then the new Y, then the newest Z: R = Rx * Ry * Rz.
[[nodiscard]] Eigen::Quaterniond rotationFromDegrees(const Vec3& degrees);
[[nodiscard]] Pose poseFrom(const InitialPose& pose);

class RandomPlacer {
 public:
  // `containerHalfExtent` > 0: samples whose sphere leaves the cube are rejected too.
  RandomPlacer(std::uint64_t seed, double containerHalfExtent);

  // A body placed otherwise (explicit pose) that random bodies must keep clear of.
  void reserve(const BoundingSphere& worldSphere);

  // One body of `group` per mesh bounding sphere in `meshSpheres`. The random numbers are drawn
  // per body in a fixed order (position until accepted, orientation, linear velocity, angular
  // velocity), so a recording depends only on the seed and the groups placed before. Throws
  // RunError when a body cannot be placed after many tries.
  [[nodiscard]] std::vector<BodyStart> place(const BodyGroup& group,
                                             std::span<const BoundingSphere> meshSpheres);

 private:
  [[nodiscard]] double uniform();  // [0, 1), 53 bits: same numbers on every standard library
  [[nodiscard]] double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  [[nodiscard]] Eigen::Vector3d unitVector();
  [[nodiscard]] Eigen::Quaterniond rotation();
  [[nodiscard]] bool isFree(const Eigen::Vector3d& centre, double radius, double gap) const;

  std::mt19937_64 rng_;
  double containerHalfExtent_;
  std::vector<BoundingSphere> placed_;
};

}  // namespace cdb
