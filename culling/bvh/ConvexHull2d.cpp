#include "culling/bvh/ConvexHull2d.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace cdb {
namespace {

// Twice the signed area of (o, a, b): positive when the turn o -> a -> b is counter-clockwise.
double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// Akl-Toussaint: the extreme points in eight directions span a convex polygon, and no point
// strictly inside it can be a hull vertex. Dropping those before sorting makes large sets (a mesh
// node's projected vertices) cost little more than one linear pass.
std::vector<Eigen::Vector2d> withoutInteriorPoints(std::span<const Eigen::Vector2d> points) {
  // Support directions in counter-clockwise order, so the extremes are in hull order too.
  static constexpr double kDirections[8][2] = {{1, 0},  {1, 1},   {0, 1},  {-1, 1},
                                               {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
  std::array<Eigen::Vector2d, 8> extreme;
  extreme.fill(points[0]);  // callers pass more than a few points
  std::array<double, 8> reach;
  reach.fill(-INFINITY);
  for (const auto& p : points) {
    for (int d = 0; d < 8; ++d) {
      const double s = kDirections[d][0] * p.x() + kDirections[d][1] * p.y();
      if (s > reach[d]) {
        reach[d] = s;
        extreme[d] = p;
      }
    }
  }
  std::vector<Eigen::Vector2d> polygon;
  for (const auto& e : extreme)
    if (polygon.empty() || (e != polygon.back() && e != polygon.front())) polygon.push_back(e);
  if (polygon.size() < 3) return {points.begin(), points.end()};

  std::vector<Eigen::Vector2d> kept;
  for (const auto& p : points) {
    bool inside = true;
    for (std::size_t i = 0; i < polygon.size() && inside; ++i)
      inside = cross(polygon[i], polygon[(i + 1) % polygon.size()], p) > 0;
    if (!inside) kept.push_back(p);
  }
  return kept;
}

}  // namespace

std::vector<Eigen::Vector2d> convexHull2d(std::span<const Eigen::Vector2d> points) {
  // Below a few dozen points the filter saves less than it costs.
  std::vector<Eigen::Vector2d> sorted =
      points.size() > 64 ? withoutInteriorPoints(points)
                         : std::vector<Eigen::Vector2d>(points.begin(), points.end());
  const auto less = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  };
  std::sort(sorted.begin(), sorted.end(), less);
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  if (sorted.size() < 3) return sorted;

  // Lower chain left to right, then upper chain right to left; popping on cross <= 0 drops
  // collinear points, so every hull vertex is a strict corner.
  std::vector<Eigen::Vector2d> hull(2 * sorted.size());
  std::size_t k = 0;
  for (const auto& p : sorted) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p) <= 0) --k;
    hull[k++] = p;
  }
  const std::size_t lowerSize = k + 1;
  for (std::size_t i = sorted.size() - 1; i-- > 0;) {
    while (k >= lowerSize && cross(hull[k - 2], hull[k - 1], sorted[i]) <= 0) --k;
    hull[k++] = sorted[i];
  }
  hull.resize(k - 1);  // the last point repeats the first
  return hull;
}

}  // namespace cdb
