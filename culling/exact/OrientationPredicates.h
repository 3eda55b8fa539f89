#pragma once
// Orientation predicates with exact signs: a floating-point evaluation guarded by Shewchuk's
// static relative error bound ("Adaptive Precision Floating-Point Arithmetic and Fast Robust
// Geometric Predicates", 1997, errboundA), and an exact evaluation in GMP rationals when the bound
// cannot decide. Every double is a rational, so the signs are those of the real determinants.
#include <Eigen/Core>
#include <cmath>
#include <limits>

namespace cdb::predicates {

// Half an ulp of 1: the unit roundoff of double.
inline constexpr double kEpsilon = std::numeric_limits<double>::epsilon() * 0.5;
inline constexpr double kOrient2dBound = (3.0 + 16.0 * kEpsilon) * kEpsilon;
inline constexpr double kOrient3dBound = (7.0 + 56.0 * kEpsilon) * kEpsilon;
// Below this magnitude products may have underflowed and the relative bound no longer holds.
inline constexpr double kUnderflowGuard = 1e-280;

// Exact signs for when the filter fails. Non-finite input gives 0 instead of undefined behaviour.
[[nodiscard]] int orient2dExact(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                const Eigen::Vector2d& c);
[[nodiscard]] int orient3dExact(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                const Eigen::Vector3d& c, const Eigen::Vector3d& d);

// The sign decided from a rounded value and its error bound, or 2 when undecided.
[[nodiscard]] inline int filteredSign(double value, double errorBound) {
  if (!(errorBound >= kUnderflowGuard)) return 2;  // also exact zeros and NaN: rare, left to GMP
  if (value > errorBound) return 1;
  if (-value > errorBound) return -1;
  return 2;
}

// Sign of (a - c) x (b - c): +1 when a, b, c turn counter-clockwise.
[[nodiscard]] inline int orient2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                  const Eigen::Vector2d& c) {
  const double left = (a.x() - c.x()) * (b.y() - c.y());
  const double right = (a.y() - c.y()) * (b.x() - c.x());
  const int s = filteredSign(left - right, kOrient2dBound * (std::abs(left) + std::abs(right)));
  return s != 2 ? s : orient2dExact(a, b, c);
}

// Sign of det[a - d; b - d; c - d] = ((a - d) x (b - d)) . (c - d).
[[nodiscard]] inline int orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                  const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  const Eigen::Vector3d ad = a - d, bd = b - d, cd = c - d;
  const double bxcy = bd.x() * cd.y(), cxby = cd.x() * bd.y();
  const double cxay = cd.x() * ad.y(), axcy = ad.x() * cd.y();
  const double axby = ad.x() * bd.y(), bxay = bd.x() * ad.y();
  const double det = ad.z() * (bxcy - cxby) + bd.z() * (cxay - axcy) + cd.z() * (axby - bxay);
  const double permanent = (std::abs(bxcy) + std::abs(cxby)) * std::abs(ad.z()) +
                           (std::abs(cxay) + std::abs(axcy)) * std::abs(bd.z()) +
                           (std::abs(axby) + std::abs(bxay)) * std::abs(cd.z());
  const int s = filteredSign(det, kOrient3dBound * permanent);
  return s != 2 ? s : orient3dExact(a, b, c, d);
}

}  // namespace cdb::predicates
