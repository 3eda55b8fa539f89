#pragma once
// The 2D convex hull of a point set (Andrew's monotone chain), used to fit the minimum-area
// rectangle of a projected vertex set.
#include <Eigen/Core>
#include <span>
#include <vector>

namespace cdb {

// The hull vertices in counter-clockwise order, starting at the lexicographically smallest point,
// without duplicate or collinear points. Fewer than three points come back for degenerate input:
// none for no input, one when all points coincide, the two ends when all points are collinear.
[[nodiscard]] std::vector<Eigen::Vector2d> convexHull2d(std::span<const Eigen::Vector2d> points);

}  // namespace cdb
