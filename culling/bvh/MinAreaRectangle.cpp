#include "culling/bvh/MinAreaRectangle.h"

#include <cstddef>
#include <vector>

#include "culling/bvh/ConvexHull2d.h"

namespace cdb {
namespace {

Eigen::Vector2d perp(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }

// The rectangle with sides along `u` and perp(u) spanning [lo, hi] in those coordinates, turned
// by quarter turns so that its axis lies in [0, pi/2): one canonical form per rectangle.
Rectangle2d makeRectangle(Eigen::Vector2d u, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  Rectangle2d r;
  r.center = u * (0.5 * (lo.x() + hi.x())) + perp(u) * (0.5 * (lo.y() + hi.y()));
  Eigen::Vector2d half = 0.5 * (hi - lo);
  for (int turn = 0; turn < 4 && !(u.x() > 0 && u.y() >= 0); ++turn) {
    u = perp(u);
    half = {half.y(), half.x()};
  }
  r.axis = u;
  r.halfExtents = half;
  return r;
}

}  // namespace

Rectangle2d minAreaRectangleOfHull(std::span<const Eigen::Vector2d> hull) {
  const std::size_t n = hull.size();
  if (n == 0) return {};
  if (n == 1) return makeRectangle(Eigen::Vector2d::UnitX(), hull[0], hull[0]);
  if (n == 2) {
    const Eigen::Vector2d u = (hull[1] - hull[0]).normalized();
    const Eigen::Vector2d a(u.dot(hull[0]), perp(u).dot(hull[0]));
    const Eigen::Vector2d b(u.dot(hull[1]), a.y());
    return makeRectangle(u, a, b);
  }

  const auto at = [&](std::size_t i) -> const Eigen::Vector2d& { return hull[i % n]; };
  // Three calipers for edge i (direction u, inward normal v): the farthest point along u (right),
  // along v (top) and against u (left). Each only moves forward as i advances, so one sweep is
  // linear; the step bound stops a caliper from lapping the hull on rounding ties.
  std::size_t right = 0, top = 0, left = 0;
  double bestArea = 0;
  Rectangle2d best;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d u = (at(i + 1) - at(i)).normalized();
    const Eigen::Vector2d v = perp(u);
    if (i == 0) right = 1;
    for (std::size_t s = 0; s < n && u.dot(at(right + 1) - at(right)) > 0; ++s) ++right;
    if (i == 0) top = right;
    for (std::size_t s = 0; s < n && v.dot(at(top + 1) - at(top)) > 0; ++s) ++top;
    if (i == 0) left = top;
    for (std::size_t s = 0; s < n && u.dot(at(left + 1) - at(left)) < 0; ++s) ++left;

    const Eigen::Vector2d& o = at(i);
    const double width = u.dot(at(right) - o) - u.dot(at(left) - o);
    const double height = v.dot(at(top) - o);
    const double area = width * height;
    if (i == 0 || area < bestArea) {
      bestArea = area;
      const Eigen::Vector2d lo(u.dot(at(left)), v.dot(o));
      const Eigen::Vector2d hi(u.dot(at(right)), v.dot(at(top)));
      best = makeRectangle(u, lo, hi);
    }
  }
  return best;
}

Rectangle2d minAreaRectangle(std::span<const Eigen::Vector2d> points) {
  const std::vector<Eigen::Vector2d> hull = convexHull2d(points);
  return minAreaRectangleOfHull(hull);
}

}  // namespace cdb
