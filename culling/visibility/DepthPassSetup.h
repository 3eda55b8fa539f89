#pragma once
// Where a pass puts the world in the depth buffer: CULLIDE's orthographic view along a direction
// (Govindaraju et al. 2003), fitted to the tested bounds, and the depth-range split that lets two
// passes share one clear (thesis 3.2). Pure arithmetic, so it is tested without a GL context.
#include <Eigen/Geometry>

#include "culling/visibility/VisibilityBackend.h"

namespace cdb {

struct DepthPassSetup {
  // World -> (x, y in pixels of the depth buffer, t in [0, 1] along the view direction, 1).
  Eigen::Matrix4d worldToScreen = Eigen::Matrix4d::Identity();
  // World -> clip space of the same view (NDC z = 2 t - 1, w = 1).
  Eigen::Matrix4d worldToClip = Eigen::Matrix4d::Identity();
  int resolution = 0;
  // glDepthRange(depthNear, depthFar): stored depth of t = 0 and t = 1. depthNear > depthFar is
  // the reversed order (nearer = larger stored depth).
  double depthNear = 0.0;
  double depthFar = 1.0;
  bool clear = true;
  double clearDepth = 1.0;
  // Float rounding of the vertex transforms plus a few ulps of a float32 depth, in stored-depth
  // units: conservative depths move by this much toward "occluded".
  double depthEpsilon = 0.0;
  // Widening beyond the pixel square, in pixels: rasteriser snapping and transform rounding.
  double coverageMarginPx = 0.0;

  [[nodiscard]] bool reversed() const { return depthNear > depthFar; }
};

// The fitted view: `view.bounds` padded so that nothing inside it is clipped (a percent and two
// pixels across, five percent in depth). Throws InputError on a resolution below 1, a non-finite
// bounds box or a zero direction; empty bounds give a unit box at the origin.
[[nodiscard]] DepthPassSetup makeDepthPassSetup(const ViewSpec& view, DepthUse depth);

// Orthonormal (u, v, w) with w = direction: u and v are the screen's x and y.
[[nodiscard]] Eigen::Matrix3d viewBasis(const Eigen::Vector3d& direction);

}  // namespace cdb
