#pragma once
// An independent, slow, fully rational triangle-triangle test: the separating axis theorem over
// every direction along which two triangles' closest features can be separated (face normals,
// edge x edge, vertex - vertex, and the perpendicular from a vertex to an edge's line). Exact for
// any input, degenerate triangles included, because all arithmetic is in GMP rationals.
#include <gmpxx.h>

#include <Eigen/Core>
#include <array>
#include <vector>

namespace cdb::testing {

using Q3 = std::array<mpq_class, 3>;

inline Q3 toRational(const Eigen::Vector3d& v) {
  return {mpq_class(v.x()), mpq_class(v.y()), mpq_class(v.z())};
}
inline Q3 minus(const Q3& a, const Q3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Q3 cross(const Q3& a, const Q3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline mpq_class dot(const Q3& a, const Q3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

inline bool separatedAlong(const Q3& axis, const std::array<Q3, 3>& a, const std::array<Q3, 3>& b) {
  if (sgn(axis[0]) == 0 && sgn(axis[1]) == 0 && sgn(axis[2]) == 0) return false;
  mpq_class minA = dot(axis, a[0]), maxA = minA, minB = dot(axis, b[0]), maxB = minB;
  for (int i = 1; i < 3; ++i) {
    const mpq_class da = dot(axis, a[i]), db = dot(axis, b[i]);
    if (da < minA) minA = da;
    if (da > maxA) maxA = da;
    if (db < minB) minB = db;
    if (db > maxB) maxB = db;
  }
  return maxA < minB || maxB < minA;
}

inline bool referenceTrianglesIntersect(const std::array<Eigen::Vector3d, 3>& ta,
                                        const std::array<Eigen::Vector3d, 3>& tb) {
  const std::array<Q3, 3> a = {toRational(ta[0]), toRational(ta[1]), toRational(ta[2])};
  const std::array<Q3, 3> b = {toRational(tb[0]), toRational(tb[1]), toRational(tb[2])};
  std::array<Q3, 3> ea, eb;
  for (int i = 0; i < 3; ++i) {
    ea[i] = minus(a[(i + 1) % 3], a[i]);
    eb[i] = minus(b[(i + 1) % 3], b[i]);
  }
  std::vector<Q3> axes;
  axes.push_back(cross(ea[0], ea[1]));
  axes.push_back(cross(eb[0], eb[1]));
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      axes.push_back(cross(ea[i], eb[j]));
      axes.push_back(minus(a[i], b[j]));
      // From the line of edge j of one triangle to vertex i of the other, perpendicular to it.
      axes.push_back(cross(eb[j], cross(minus(a[i], b[j]), eb[j])));
      axes.push_back(cross(ea[j], cross(minus(b[i], a[j]), ea[j])));
    }
  }
  for (const Q3& axis : axes)
    if (separatedAlong(axis, a, b)) return false;
  return true;
}

}  // namespace cdb::testing
