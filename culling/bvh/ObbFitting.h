#pragma once
// Oriented bounding boxes of a set of mesh triangles (thesis 3.4.1.1): axes from the area-weighted
// covariance of the triangles, optionally improved by optimizing principal components, and the
// offset that keeps thin contacts visible at finite frame-buffer resolution (3.4.1).
#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "core/OrientedBox.h"
#include "scenes/Mesh.h"

namespace cdb {

// The box along the covariance axes around the vertices of `triangles`. No triangles give a zero
// box at the origin.
[[nodiscard]] OrientedBox fitCovarianceObb(const Mesh& mesh,
                                           std::span<const std::uint32_t> triangles);

// Optimizing principal components (Ericson, Real-Time Collision Detection 4.4.4): each covariance
// axis in turn is kept and the minimum-area rectangle of the vertices projected onto the plane
// across it gives the other two. The smallest of the three boxes is kept unless the covariance
// box is no larger, so the result never has a larger volume than fitCovarianceObb.
[[nodiscard]] OrientedBox fitOptimizedObb(const Mesh& mesh,
                                          std::span<const std::uint32_t> triangles);

// `box` with `offset` added to each half extent.
[[nodiscard]] OrientedBox grown(const OrientedBox& box, double offset);

// Whether every corner of `inner` lies in `outer`, allowing `tolerance` outside each face.
[[nodiscard]] bool boxContains(const OrientedBox& outer, const OrientedBox& inner,
                               double tolerance = 0);

// Smaller volume first; among equal volumes (flat sets, where every box has volume zero) the
// smaller surface area.
[[nodiscard]] bool smallerBox(const OrientedBox& a, const OrientedBox& b);

// --- the steps of the two fits, for fitting other point sets --------------------------------

// The positions of the vertices used by `triangles`, each vertex once, in index order.
[[nodiscard]] std::vector<Eigen::Vector3d> verticesOf(const Mesh& mesh,
                                                      std::span<const std::uint32_t> triangles);

// The area-weighted covariance of the triangles' surface (Gottschalk, Lin and Manocha; Eberly):
// C_jk = sum_i A_i / (12 A_H) (9 c_j c_k + p_j p_k + q_j q_k + r_j r_k) - cH_j cH_k.
// When the total area is zero it is pointCovariance of their vertices instead. The result
// depends on the set of triangles only, not on their order in the span.
[[nodiscard]] Eigen::Matrix3d triangleCovariance(const Mesh& mesh,
                                                 std::span<const std::uint32_t> triangles);

// The covariance of a point set, each point weighted equally.
[[nodiscard]] Eigen::Matrix3d pointCovariance(std::span<const Eigen::Vector3d> points);

// The eigenvectors of a covariance matrix as right-handed orthonormal columns, largest spread
// first, each one's sign fixed so the result does not depend on the solver's choice. The identity
// when the matrix is zero (all points at one place).
[[nodiscard]] Eigen::Matrix3d principalAxes(const Eigen::Matrix3d& covariance);

// The tightest box with the given orthonormal axes (columns) around `points`.
[[nodiscard]] OrientedBox boxAlongAxes(std::span<const Eigen::Vector3d> points,
                                       const Eigen::Matrix3d& axes);

// The box whose axes are frame.col(k) and the sides of the minimum-area rectangle around the
// points projected onto the plane of the frame's other two columns.
[[nodiscard]] OrientedBox boxAroundAxis(std::span<const Eigen::Vector3d> points,
                                        const Eigen::Matrix3d& frame, int k);

// The smallest of the box along `principal` and boxAroundAxis for each of its three columns.
[[nodiscard]] OrientedBox optimizedBox(std::span<const Eigen::Vector3d> points,
                                       const Eigen::Matrix3d& principal);

}  // namespace cdb
