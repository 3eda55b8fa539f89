#include "culling/bvh/ObbFitting.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "culling/bvh/MinAreaRectangle.h"

namespace cdb {
namespace {

Eigen::Vector3d vertex(const Mesh& mesh, std::uint32_t i) {
  return mesh.vertices[i].cast<double>();
}

double surfaceArea(const OrientedBox& box) {
  const Eigen::Vector3d& h = box.halfExtents;
  return 8.0 * (h.x() * h.y() + h.y() * h.z() + h.z() * h.x());
}

}  // namespace

OrientedBox fitCovarianceObb(const Mesh& mesh, std::span<const std::uint32_t> triangles) {
  if (triangles.empty()) return {};
  return boxAlongAxes(verticesOf(mesh, triangles),
                      principalAxes(triangleCovariance(mesh, triangles)));
}

OrientedBox fitOptimizedObb(const Mesh& mesh, std::span<const std::uint32_t> triangles) {
  if (triangles.empty()) return {};
  return optimizedBox(verticesOf(mesh, triangles),
                      principalAxes(triangleCovariance(mesh, triangles)));
}

OrientedBox grown(const OrientedBox& box, double offset) {
  OrientedBox g = box;
  g.halfExtents.array() += offset;
  return g;
}

bool boxContains(const OrientedBox& outer, const OrientedBox& inner, double tolerance) {
  const Eigen::Vector3d limit = outer.halfExtents.array() + tolerance;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d d = outer.axes.transpose() * (inner.corner(i) - outer.center);
    if ((d.cwiseAbs().array() > limit.array()).any()) return false;
  }
  return true;
}

bool smallerBox(const OrientedBox& a, const OrientedBox& b) {
  const double va = a.volume(), vb = b.volume();
  return va < vb || (va == vb && surfaceArea(a) < surfaceArea(b));
}

std::vector<Eigen::Vector3d> verticesOf(const Mesh& mesh,
                                        std::span<const std::uint32_t> triangles) {
  std::vector<std::uint32_t> indices;
  indices.reserve(3 * triangles.size());
  for (const std::uint32_t t : triangles)
    for (const std::uint32_t v : mesh.triangles[t]) indices.push_back(v);
  std::sort(indices.begin(), indices.end());
  indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
  std::vector<Eigen::Vector3d> points;
  points.reserve(indices.size());
  for (const std::uint32_t v : indices) points.push_back(vertex(mesh, v));
  return points;
}

Eigen::Matrix3d triangleCovariance(const Mesh& mesh, std::span<const std::uint32_t> triangles) {
  if (triangles.empty()) return Eigen::Matrix3d::Zero();
  // Summing in index order makes the result depend on the set alone, not on the order a caller
  // keeps it in: near-equal eigenvalues (a torus' two in-plane axes) would otherwise turn
  // rounding differences into different axes.
  std::vector<std::uint32_t> ordered(triangles.begin(), triangles.end());
  std::sort(ordered.begin(), ordered.end());
  // Covariance does not depend on the origin; measuring from a vertex of the set keeps the
  // second moments small for meshes far from their local origin.
  const Eigen::Vector3d origin = vertex(mesh, mesh.triangles[ordered[0]][0]);
  Eigen::Matrix3d moments = Eigen::Matrix3d::Zero();
  Eigen::Vector3d weightedCentroid = Eigen::Vector3d::Zero();
  double totalArea = 0;
  for (const std::uint32_t t : ordered) {
    const auto& tri = mesh.triangles[t];
    const Eigen::Vector3d p = vertex(mesh, tri[0]) - origin;
    const Eigen::Vector3d q = vertex(mesh, tri[1]) - origin;
    const Eigen::Vector3d r = vertex(mesh, tri[2]) - origin;
    const double area = 0.5 * (p - q).cross(p - r).norm();
    const Eigen::Vector3d c = (p + q + r) / 3.0;
    moments += (area / 12.0) * (9.0 * c * c.transpose() + p * p.transpose() + q * q.transpose() +
                                r * r.transpose());
    weightedCentroid += area * c;
    totalArea += area;
  }
  if (totalArea > 0) {
    const Eigen::Vector3d cH = weightedCentroid / totalArea;
    return moments / totalArea - cH * cH.transpose();
  }
  // Zero area (every triangle degenerate): the vertices are all that describe the shape.
  return pointCovariance(verticesOf(mesh, triangles));
}

Eigen::Matrix3d pointCovariance(std::span<const Eigen::Vector3d> points) {
  if (points.empty()) return Eigen::Matrix3d::Zero();
  const Eigen::Vector3d origin = points[0];  // as above, for small second moments
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) mean += p - origin;
  mean /= double(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto& p : points) {
    const Eigen::Vector3d d = p - origin - mean;
    covariance += d * d.transpose();
  }
  return covariance / double(points.size());
}

Eigen::Matrix3d principalAxes(const Eigen::Matrix3d& covariance) {
  // A zero matrix (all points at one place) or a failed solve leaves the identity axes.
  if (!covariance.allFinite() || covariance.isZero(0)) return Eigen::Matrix3d::Identity();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  if (solver.info() != Eigen::Success) return Eigen::Matrix3d::Identity();
  // Eigenvalues ascend, so the largest spread is the last column. Each eigenvector's sign is
  // arbitrary: pointing its largest component positive makes equal input give equal boxes.
  const auto signFixed = [](Eigen::Vector3d v) {
    Eigen::Index largest = 0;
    v.cwiseAbs().maxCoeff(&largest);
    return v[largest] < 0 ? Eigen::Vector3d(-v) : v;
  };
  const Eigen::Matrix3d& v = solver.eigenvectors();
  Eigen::Matrix3d axes;
  axes.col(0) = signFixed(v.col(2)).normalized();
  axes.col(1) = signFixed(v.col(1)).normalized();
  axes.col(2) = axes.col(0).cross(axes.col(1)).normalized();
  return axes;
}

OrientedBox boxAlongAxes(std::span<const Eigen::Vector3d> points, const Eigen::Matrix3d& axes) {
  if (points.empty()) return {{}, axes, {}};
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY);
  Eigen::Vector3d hi = Eigen::Vector3d::Constant(-INFINITY);
  for (const auto& p : points) {
    const Eigen::Vector3d x = axes.transpose() * p;
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  return {axes * (0.5 * (lo + hi)), axes, 0.5 * (hi - lo)};
}

OrientedBox boxAroundAxis(std::span<const Eigen::Vector3d> points, const Eigen::Matrix3d& frame,
                          int k) {
  // (b1, b2, a) is a cyclic shift of a right-handed frame, hence right-handed itself.
  const Eigen::Vector3d a = frame.col(k);
  const Eigen::Vector3d b1 = frame.col((k + 1) % 3);
  const Eigen::Vector3d b2 = frame.col((k + 2) % 3);
  std::vector<Eigen::Vector2d> projected;
  projected.reserve(points.size());
  for (const auto& p : points) projected.emplace_back(b1.dot(p), b2.dot(p));
  const Rectangle2d rectangle = minAreaRectangle(projected);
  Eigen::Matrix3d axes;
  axes.col(0) = (rectangle.axis.x() * b1 + rectangle.axis.y() * b2).normalized();
  axes.col(1) = a.cross(axes.col(0)).normalized();
  axes.col(2) = a;
  return boxAlongAxes(points, axes);
}

OrientedBox optimizedBox(std::span<const Eigen::Vector3d> points,
                         const Eigen::Matrix3d& principal) {
  OrientedBox best = boxAlongAxes(points, principal);
  for (int k = 0; k < 3; ++k) {
    const OrientedBox candidate = boxAroundAxis(points, principal, k);
    if (smallerBox(candidate, best)) best = candidate;
  }
  return best;
}

}  // namespace cdb
