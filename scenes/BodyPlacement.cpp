#include "scenes/BodyPlacement.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "core/Errors.h"

namespace cdb {

namespace {

// Consecutive rejections of one body before giving up: at that point the region is so full that
// further tries would only stall the run. env3 fills its cube to 30% at 200 tori, near where
// random sequential placement jams: 20,000 tries failed for 6 of the seeds 1-10 (the sweep's 10
// repeats), 2,000,000 place all of them in ~0.1 s; a region that cannot hold the group fails in
// about a second.
constexpr int kMaxTriesPerBody = 2000000;

std::string format(const Vec3& v) {
  std::ostringstream out;
  out << "(" << v[0] << ", " << v[1] << ", " << v[2] << ")";
  return out.str();
}

}  // namespace

Eigen::Quaterniond rotationFromDegrees(const Vec3& degrees) {
  constexpr double toRadians = std::numbers::pi / 180.0;
  const Eigen::Quaterniond q = Eigen::AngleAxisd(degrees[0] * toRadians, Eigen::Vector3d::UnitX()) *
                               Eigen::AngleAxisd(degrees[1] * toRadians, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(degrees[2] * toRadians, Eigen::Vector3d::UnitZ());
  return q.normalized();
}

Pose poseFrom(const InitialPose& pose) {
  Pose result;
  result.rotation = rotationFromDegrees(pose.rotationDegrees);
  result.translation = Eigen::Vector3d(pose.position[0], pose.position[1], pose.position[2]);
  return result;
}

RandomPlacer::RandomPlacer(std::uint64_t seed, double containerHalfExtent)
    : rng_(seed), containerHalfExtent_(containerHalfExtent) {}

void RandomPlacer::reserve(const BoundingSphere& worldSphere) { placed_.push_back(worldSphere); }

double RandomPlacer::uniform() { return double(rng_() >> 11) * 0x1.0p-53; }

Eigen::Vector3d RandomPlacer::unitVector() {
  const double z = uniform(-1.0, 1.0);
  const double phi = uniform(0.0, 2.0 * std::numbers::pi);
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

Eigen::Quaterniond RandomPlacer::rotation() {
  // Shoemake's uniform quaternion.
  const double u1 = uniform(), u2 = uniform(), u3 = uniform();
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  const double t2 = 2.0 * std::numbers::pi * u2, t3 = 2.0 * std::numbers::pi * u3;
  return Eigen::Quaterniond(b * std::cos(t3), a * std::sin(t2), a * std::cos(t2), b * std::sin(t3))
      .normalized();
}

bool RandomPlacer::isFree(const Eigen::Vector3d& centre, double radius, double gap) const {
  if (containerHalfExtent_ > 0 && (centre.cwiseAbs().array() + radius > containerHalfExtent_).any()) {
    return false;
  }
  for (const auto& other : placed_) {
    const double clearance = radius + other.radius + gap;
    if ((centre - other.centre).squaredNorm() < clearance * clearance) return false;
  }
  return true;
}

std::vector<BodyStart> RandomPlacer::place(const BodyGroup& group,
                                           std::span<const BoundingSphere> meshSpheres) {
  const RandomPlacement spec = group.placement.value_or(RandomPlacement{});
  const Eigen::Vector3d lo(spec.regionMin[0], spec.regionMin[1], spec.regionMin[2]);
  const Eigen::Vector3d hi(spec.regionMax[0], spec.regionMax[1], spec.regionMax[2]);
  std::vector<BodyStart> starts;
  starts.reserve(meshSpheres.size());
  for (std::size_t body = 0; body < meshSpheres.size(); ++body) {
    const BoundingSphere& meshSphere = meshSpheres[body];
    Eigen::Vector3d centre;
    int tries = 0;
    do {
      if (++tries > kMaxTriesPerBody) {
        std::ostringstream message;
        message << "cannot place " << meshSpheres.size() << " bodies of group " << group.name << " in region "
                << format(spec.regionMin) << ".." << format(spec.regionMax);
        if (containerHalfExtent_ > 0) message << " inside the cube of half extent " << containerHalfExtent_;
        message << " (placed " << body << "; bounding radius " << meshSphere.radius << ", minGap "
                << spec.minGap << "): enlarge region";
        throw RunError(message.str());
      }
      for (int k = 0; k < 3; ++k) centre[k] = uniform(lo[k], hi[k]);
    } while (!isFree(centre, meshSphere.radius, spec.minGap));
    placed_.push_back({centre, meshSphere.radius});

    BodyStart start;
    start.pose.rotation = spec.randomOrientation ? rotation() : Eigen::Quaterniond::Identity();
    // The sampled point is where the bounding sphere's centre goes.
    start.pose.translation = centre - start.pose.rotation * meshSphere.centre;
    const double speed = uniform(spec.speedMin, spec.speedMax);
    start.linearVelocity = speed * unitVector();
    const double angularSpeed = uniform(0.0, spec.angularSpeedMax);
    start.angularVelocity = angularSpeed * unitVector();
    starts.push_back(start);
  }
  return starts;
}

}  // namespace cdb
