#pragma once
// The minimum-area enclosing rectangle of a 2D point set by rotating calipers over its convex
// hull: the optimal rectangle has a side collinear with a hull edge (Freeman and Shapira), so only
// the hull's edge directions need to be tried.
#include <Eigen/Core>
#include <span>

namespace cdb {

struct Rectangle2d {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  // Unit direction of the first side, at an angle in [0, pi/2) from +x; the second side runs along
  // (-axis.y, axis.x).
  Eigen::Vector2d axis = Eigen::Vector2d::UnitX();
  Eigen::Vector2d halfExtents = Eigen::Vector2d::Zero();  // along axis, then along its normal

  [[nodiscard]] double area() const { return 4.0 * halfExtents.x() * halfExtents.y(); }
};

// The smallest-area rectangle containing `points`. Coincident points give a zero rectangle at
// that point, collinear points a zero-width rectangle along their line, no points a zero rectangle
// at the origin. Ties go to the first hull edge found, so the result is deterministic.
[[nodiscard]] Rectangle2d minAreaRectangle(std::span<const Eigen::Vector2d> points);

// The same over points already forming a counter-clockwise convex hull without collinear points
// (as convexHull2d returns them); linear in the hull size.
[[nodiscard]] Rectangle2d minAreaRectangleOfHull(std::span<const Eigen::Vector2d> hull);

}  // namespace cdb
