#pragma once
// The exact triangle-triangle test of the exact phase and of the ground truth: Guigue and
// Devillers, "Fast and Robust Triangle-Triangle Overlap Test Using Orientation Predicates"
// (Journal of Graphics Tools 8(1), 2003), with every orientation sign computed exactly.
#include <Eigen/Core>
#include <array>

namespace cdb {

// True when the closed triangles (p1, q1, r1) and (p2, q2, r2) share a point: crossing, touching at
// a vertex or along an edge, a vertex on the other's face, or overlapping in a common plane.
// Every branch is taken on the exact sign of an orientation determinant of the given doubles, so
// the answer is exact for these coordinates, however close to touching they are.
// A degenerate triangle (repeated or collinear vertices, zero area) is taken as the segment or
// point it covers, and tested as such. Coordinates must be finite; NaN or infinite ones give an
// unspecified answer, never a crash.
[[nodiscard]] bool trianglesIntersect(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1,
                                      const Eigen::Vector3d& r1, const Eigen::Vector3d& p2,
                                      const Eigen::Vector3d& q2, const Eigen::Vector3d& r2);

[[nodiscard]] inline bool trianglesIntersect(const std::array<Eigen::Vector3d, 3>& a,
                                             const std::array<Eigen::Vector3d, 3>& b) {
  return trianglesIntersect(a[0], a[1], a[2], b[0], b[1], b[2]);
}

}  // namespace cdb
