#include "culling/visibility/DepthPassSetup.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/Errors.h"

namespace cdb {

namespace {

// Stored depths of the two passes that share a clear. The gap between the halves absorbs the
// conservative epsilon; the clear value lies in it, so an untouched pixel reads as "far" in both
// orders (above the first half, below the second).
constexpr double kFirstHalfFar = 0.49;
constexpr double kSecondHalfFar = 0.51;
constexpr double kSharedClear = 0.5;

constexpr double kFloatUlpAtOne = 1.0 / 16777216.0;  // 2^-24: a float32 ulp just below 1
constexpr double kXyPad = 0.01;
constexpr double kDepthPad = 0.05;
constexpr double kBorderPixels = 2.0;

}  // namespace

Eigen::Matrix3d viewBasis(const Eigen::Vector3d& direction) {
  const Eigen::Vector3d w = direction.normalized();
  const Eigen::Vector3d u = w.unitOrthogonal();
  const Eigen::Vector3d v = w.cross(u);
  Eigen::Matrix3d basis;
  basis << u, v, w;
  return basis;
}

DepthPassSetup makeDepthPassSetup(const ViewSpec& view, DepthUse depth) {
  if (view.resolution < 1)
    throw InputError("view resolution " + std::to_string(view.resolution) + " is below 1");
  const double dirNorm = view.direction.norm();
  if (!std::isfinite(dirNorm) || dirNorm < 1e-12)
    throw InputError("view direction must be a finite non-zero vector");
  Aabb bounds = view.bounds;
  if (bounds.isEmpty())
    bounds = Aabb(Eigen::Vector3d::Constant(-1.0), Eigen::Vector3d::Constant(1.0));
  if (!bounds.min().allFinite() || !bounds.max().allFinite())
    throw InputError("view bounds are not finite (NaN or infinite poses?)");

  const Eigen::Matrix3d basis = viewBasis(view.direction);
  const Eigen::Vector3d center = bounds.center();
  // Half extents of the box along each basis axis (support of the box).
  const Eigen::Vector3d half = basis.transpose().cwiseAbs() * (bounds.sizes() * 0.5);
  const double largest = std::max(half.maxCoeff(), 1e-12);
  const double res = view.resolution;
  const double borderScale = 1.0 - 2.0 * kBorderPixels / std::max(res, 2.0 * kBorderPixels + 4.0);
  Eigen::Vector3d padded;
  for (int i = 0; i < 2; ++i)
    padded[i] = std::max(half[i], 1e-9 * largest) * (1.0 + kXyPad) / borderScale;
  padded[2] = std::max(half[2], 1e-9 * largest) * (1.0 + 2.0 * kDepthPad);

  // x_px = (u.(p - c) + hu) / (2 hu) * res, likewise y; t = (w.(p - c) + hw) / (2 hw).
  const Eigen::Vector3d scale(res / (2.0 * padded[0]), res / (2.0 * padded[1]),
                              1.0 / (2.0 * padded[2]));
  const Eigen::Vector3d offset(res * 0.5, res * 0.5, 0.5);
  DepthPassSetup s;
  s.resolution = view.resolution;
  Eigen::Matrix3d linear = scale.asDiagonal() * basis.transpose();
  s.worldToScreen.setIdentity();
  s.worldToScreen.topLeftCorner<3, 3>() = linear;
  s.worldToScreen.topRightCorner<3, 1>() = offset - linear * center;
  Eigen::Matrix4d screenToClip = Eigen::Matrix4d::Identity();
  screenToClip.diagonal().head<3>() = Eigen::Vector3d(2.0 / res, 2.0 / res, 2.0);
  screenToClip.topRightCorner<3, 1>() = Eigen::Vector3d::Constant(-1.0);
  s.worldToClip = screenToClip * s.worldToScreen;

  switch (depth) {
    case DepthUse::Fresh:
    case DepthUse::OrderIndependent:
      s.depthNear = 0.0, s.depthFar = 1.0, s.clear = true, s.clearDepth = 1.0;
      break;
    case DepthUse::SharedFirst:
      s.depthNear = 0.0, s.depthFar = kFirstHalfFar, s.clear = true, s.clearDepth = kSharedClear;
      break;
    case DepthUse::SharedSecond:
      s.depthNear = 1.0, s.depthFar = kSecondHalfFar, s.clear = false, s.clearDepth = kSharedClear;
      break;
  }

  // Float vertex transforms lose about an ulp of the largest coordinate per step; relative to the
  // depth extent that is what two surfaces meeting at a point may disagree by.
  const double magnitude =
      std::max(bounds.min().cwiseAbs().maxCoeff(), bounds.max().cwiseAbs().maxCoeff());
  const double depthRange = std::abs(s.depthFar - s.depthNear);
  s.depthEpsilon = 8.0 * kFloatUlpAtOne +
                   depthRange * 16.0 * kFloatUlpAtOne * (1.0 + magnitude / (2.0 * padded[2]));
  const double xyExtent = 2.0 * std::min(padded[0], padded[1]);
  // 1/16 pixel covers rasterisers with 4 bits of sub-pixel precision (GL's minimum).
  s.coverageMarginPx = 1.0 / 16.0 + res * 16.0 * kFloatUlpAtOne * (1.0 + magnitude / xyExtent);
  return s;
}

}  // namespace cdb
