#include "culling/exact/TriangleTriangle.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "culling/exact/OrientationPredicates.h"

namespace cdb {

namespace {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using predicates::orient2d;
using predicates::orient3d;

// ---- Plane side tests sharing one normal ----

// A triangle's plane with its normal rounded once, so the three side tests of the other
// triangle's vertices cost a dot product each. The error bound is orient3d's: the same sum of
// three (difference) x (2x2 minor) terms, only grouped around another vector.
struct TrianglePlane {
  Vec3 p, q, r;
  Vec3 normal;     // (p - r) x (q - r)
  Vec3 permanent;  // per component, the sum of the absolute values of its two products
};

TrianglePlane planeOf(const Vec3& p, const Vec3& q, const Vec3& r) {
  const Vec3 u = p - r, v = q - r;
  const double yz = u.y() * v.z(), zy = u.z() * v.y();
  const double zx = u.z() * v.x(), xz = u.x() * v.z();
  const double xy = u.x() * v.y(), yx = u.y() * v.x();
  return {
      p, q, r, Vec3(yz - zy, zx - xz, xy - yx),
      Vec3(std::abs(yz) + std::abs(zy), std::abs(zx) + std::abs(xz), std::abs(xy) + std::abs(yx))};
}

// Sign of orient3d(p, q, x, r): the side of the plane (p, q, r) that x lies on.
int sideOf(const TrianglePlane& t, const Vec3& x) {
  const Vec3 w = x - t.r;
  const double det = t.normal.x() * w.x() + t.normal.y() * w.y() + t.normal.z() * w.z();
  const double permanent = t.permanent.x() * std::abs(w.x()) + t.permanent.y() * std::abs(w.y()) +
                           t.permanent.z() * std::abs(w.z());
  const int s = predicates::filteredSign(det, predicates::kOrient3dBound * permanent);
  return s != 2 ? s : predicates::orient3dExact(t.p, t.q, x, t.r);
}

// ---- Two dimensions: coplanar and degenerate configurations ----

// Drops coordinate `axis`; the map is injective on any plane whose normal has a nonzero `axis`
// component, so incidences there are preserved exactly.
Vec2 drop(const Vec3& v, int axis) {
  return axis == 0 ? Vec2(v.y(), v.z()) : axis == 1 ? Vec2(v.z(), v.x()) : Vec2(v.x(), v.y());
}

bool collinear(const Vec3& p, const Vec3& q, const Vec3& r) {
  for (int axis = 0; axis < 3; ++axis)
    if (orient2d(drop(p, axis), drop(q, axis), drop(r, axis)) != 0) return false;
  return true;
}

// An axis along which the non-degenerate triangle (p, q, r) projects to a non-degenerate
// triangle; the largest rounded normal component is tried first as it nearly always is one.
int projectionAxis(const Vec3& p, const Vec3& q, const Vec3& r) {
  const Vec3 n = (p - r).cross(q - r).cwiseAbs();
  int order[3] = {0, 1, 2};
  std::sort(order, order + 3, [&](int a, int b) { return n[a] > n[b]; });
  for (int axis : order)
    if (orient2d(drop(p, axis), drop(q, axis), drop(r, axis)) != 0) return axis;
  return order[0];  // unreachable for a non-degenerate triangle
}

// For p collinear with a and b: whether p lies on the closed segment ab.
bool withinSegment(const Vec2& a, const Vec2& b, const Vec2& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= p.y() && p.y() <= std::max(a.y(), b.y());
}

// Closed segments ab and cd; either may be a single point.
bool segmentsIntersect2d(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const int o1 = orient2d(a, b, c), o2 = orient2d(a, b, d);
  const int o3 = orient2d(c, d, a), o4 = orient2d(c, d, b);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && withinSegment(a, b, c)) || (o2 == 0 && withinSegment(a, b, d)) ||
         (o3 == 0 && withinSegment(c, d, a)) || (o4 == 0 && withinSegment(c, d, b));
}

// Point in the closed non-degenerate triangle abc, whichever its winding.
bool pointInTriangle2d(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  const int o1 = orient2d(a, b, p), o2 = orient2d(b, c, p), o3 = orient2d(c, a, p);
  const bool negative = o1 < 0 || o2 < 0 || o3 < 0;
  const bool positive = o1 > 0 || o2 > 0 || o3 > 0;
  return !(negative && positive);
}

bool segmentTriangle2d(const Vec2& s, const Vec2& t, const Vec2& a, const Vec2& b, const Vec2& c) {
  return segmentsIntersect2d(s, t, a, b) || segmentsIntersect2d(s, t, b, c) ||
         segmentsIntersect2d(s, t, c, a) || pointInTriangle2d(s, a, b, c);
}

// Two non-degenerate triangles in one plane: an edge crossing or one containing the other.
// Simple rather than Guigue-Devillers' decision tree: exactly coplanar pairs are rare.
bool coplanarTriangles(const Vec3& p1, const Vec3& q1, const Vec3& r1, const Vec3& p2,
                       const Vec3& q2, const Vec3& r2) {
  const int axis = projectionAxis(p1, q1, r1);
  const Vec2 a[3] = {drop(p1, axis), drop(q1, axis), drop(r1, axis)};
  const Vec2 b[3] = {drop(p2, axis), drop(q2, axis), drop(r2, axis)};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (segmentsIntersect2d(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3])) return true;
  return pointInTriangle2d(a[0], b[0], b[1], b[2]) || pointInTriangle2d(b[0], a[0], a[1], a[2]);
}

// ---- Degenerate triangles as segments ----

struct Segment {
  Vec3 s, t;
};

// Collinear points ordered lexicographically are ordered along their line, so the extremes of
// that order are the ends of the segment they cover.
Segment coveredSegment(const Vec3& p, const Vec3& q, const Vec3& r) {
  const auto less = [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  const Vec3* lo = &p;
  const Vec3* hi = &p;
  for (const Vec3* v : {&q, &r}) {
    if (less(*v, *lo)) lo = v;
    if (less(*hi, *v)) hi = v;
  }
  return {*lo, *hi};
}

// Closed segment (or point) against a non-degenerate triangle.
bool segmentTriangle(const Segment& seg, const Vec3& a, const Vec3& b, const Vec3& c) {
  const int ss = orient3d(a, b, seg.s, c), st = orient3d(a, b, seg.t, c);
  if (ss * st > 0) return false;
  if (ss == 0 && st == 0) {
    const int axis = projectionAxis(a, b, c);
    return segmentTriangle2d(drop(seg.s, axis), drop(seg.t, axis), drop(a, axis), drop(b, axis),
                             drop(c, axis));
  }
  // The segment's line meets the plane at one point of the segment; it is in the closed triangle
  // unless the line passes strictly outside one edge and strictly inside another.
  const int e0 = orient3d(seg.s, seg.t, a, b);
  const int e1 = orient3d(seg.s, seg.t, b, c);
  const int e2 = orient3d(seg.s, seg.t, c, a);
  return !((e0 < 0 || e1 < 0 || e2 < 0) && (e0 > 0 || e1 > 0 || e2 > 0));
}

// Closed segments (or points) in space: coplanar, and meeting in every coordinate projection.
// One of the projections is injective on a plane holding both, so that suffices.
bool segmentSegment(const Segment& u, const Segment& v) {
  if (orient3d(u.s, u.t, v.s, v.t) != 0) return false;
  for (int axis = 0; axis < 3; ++axis)
    if (!segmentsIntersect2d(drop(u.s, axis), drop(u.t, axis), drop(v.s, axis), drop(v.t, axis)))
      return false;
  return true;
}

// Reached when all three vertices of one triangle lie in the other's plane (or that plane is
// undefined): coplanar triangles, or at least one degenerate triangle.
bool coplanarOrDegenerate(const Vec3& p1, const Vec3& q1, const Vec3& r1, const Vec3& p2,
                          const Vec3& q2, const Vec3& r2) {
  const bool flat1 = collinear(p1, q1, r1), flat2 = collinear(p2, q2, r2);
  if (!flat1 && !flat2) return coplanarTriangles(p1, q1, r1, p2, q2, r2);
  if (flat1 && flat2) return segmentSegment(coveredSegment(p1, q1, r1), coveredSegment(p2, q2, r2));
  if (flat1) return segmentTriangle(coveredSegment(p1, q1, r1), p2, q2, r2);
  return segmentTriangle(coveredSegment(p2, q2, r2), p1, q1, r1);
}

// ---- Guigue-Devillers, general position ----

// p1 is alone on its side of plane 2 and p2 alone on its side of plane 1, both triangles wound so
// that the intersection intervals on the common line can be compared with two orientations.
bool checkMinMax(const Vec3& p1, const Vec3& q1, const Vec3& r1, const Vec3& p2, const Vec3& q2,
                 const Vec3& r2) {
  if (orient3d(p2, p1, q2, q1) > 0) return false;
  if (orient3d(p2, r1, r2, p1) > 0) return false;
  return true;
}

// Permutes triangle 2 into the canonical form; (dp2, dq2, dr2) are its sides of plane 1, not all 0.
bool canonicalTriangle2(const Vec3& p1, const Vec3& q1, const Vec3& r1, const Vec3& p2,
                        const Vec3& q2, const Vec3& r2, int dp2, int dq2, int dr2) {
  if (dp2 > 0) {
    if (dq2 > 0) return checkMinMax(p1, r1, q1, r2, p2, q2);
    if (dr2 > 0) return checkMinMax(p1, r1, q1, q2, r2, p2);
    return checkMinMax(p1, q1, r1, p2, q2, r2);
  }
  if (dp2 < 0) {
    if (dq2 < 0) return checkMinMax(p1, q1, r1, r2, p2, q2);
    if (dr2 < 0) return checkMinMax(p1, q1, r1, q2, r2, p2);
    return checkMinMax(p1, r1, q1, p2, q2, r2);
  }
  if (dq2 < 0) {
    if (dr2 >= 0) return checkMinMax(p1, r1, q1, q2, r2, p2);
    return checkMinMax(p1, q1, r1, p2, q2, r2);
  }
  if (dq2 > 0) {
    if (dr2 > 0) return checkMinMax(p1, r1, q1, p2, q2, r2);
    return checkMinMax(p1, q1, r1, q2, r2, p2);
  }
  if (dr2 > 0) return checkMinMax(p1, q1, r1, r2, p2, q2);
  return checkMinMax(p1, r1, q1, r2, p2, q2);  // dr2 < 0
}

}  // namespace

bool trianglesIntersect(const Vec3& p1, const Vec3& q1, const Vec3& r1, const Vec3& p2,
                        const Vec3& q2, const Vec3& r2) {
  // Sides of triangle 1's vertices with respect to plane 2: all strictly on one side rejects.
  const TrianglePlane plane2 = planeOf(p2, q2, r2);
  const int dp1 = sideOf(plane2, p1), dq1 = sideOf(plane2, q1), dr1 = sideOf(plane2, r1);
  if (dp1 * dq1 > 0 && dp1 * dr1 > 0) return false;

  const TrianglePlane plane1 = planeOf(p1, q1, r1);
  const int dp2 = sideOf(plane1, p2), dq2 = sideOf(plane1, q2), dr2 = sideOf(plane1, r2);
  if (dp2 * dq2 > 0 && dp2 * dr2 > 0) return false;

  // All three zero on one side means coplanar triangles or a degenerate one (no plane at all);
  // otherwise both triangles are proper and cross each other's plane.
  if ((dp1 == 0 && dq1 == 0 && dr1 == 0) || (dp2 == 0 && dq2 == 0 && dr2 == 0))
    return coplanarOrDegenerate(p1, q1, r1, p2, q2, r2);

  // Permutes triangle 1 so that p1 is alone on its side of plane 2.
  if (dp1 > 0) {
    if (dq1 > 0) return canonicalTriangle2(r1, p1, q1, p2, r2, q2, dp2, dr2, dq2);
    if (dr1 > 0) return canonicalTriangle2(q1, r1, p1, p2, r2, q2, dp2, dr2, dq2);
    return canonicalTriangle2(p1, q1, r1, p2, q2, r2, dp2, dq2, dr2);
  }
  if (dp1 < 0) {
    if (dq1 < 0) return canonicalTriangle2(r1, p1, q1, p2, q2, r2, dp2, dq2, dr2);
    if (dr1 < 0) return canonicalTriangle2(q1, r1, p1, p2, q2, r2, dp2, dq2, dr2);
    return canonicalTriangle2(p1, q1, r1, p2, r2, q2, dp2, dr2, dq2);
  }
  if (dq1 < 0) {
    if (dr1 >= 0) return canonicalTriangle2(q1, r1, p1, p2, r2, q2, dp2, dr2, dq2);
    return canonicalTriangle2(p1, q1, r1, p2, q2, r2, dp2, dq2, dr2);
  }
  if (dq1 > 0) {
    if (dr1 > 0) return canonicalTriangle2(p1, q1, r1, p2, r2, q2, dp2, dr2, dq2);
    return canonicalTriangle2(q1, r1, p1, p2, q2, r2, dp2, dq2, dr2);
  }
  if (dr1 > 0) return canonicalTriangle2(r1, p1, q1, p2, q2, r2, dp2, dq2, dr2);
  return canonicalTriangle2(r1, p1, q1, p2, r2, q2, dp2, dr2, dq2);  // dr1 < 0
}

}  // namespace cdb
