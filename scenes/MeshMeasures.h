#pragma once
// Measures of a mesh that the dynamics needs: whether it encloses a volume (then its mass comes
// from the mesh), its signed volume, and the bounding sphere used for placement and proxies.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "scenes/Mesh.h"

namespace cdb {

struct BoundingSphere {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // in mesh-local coordinates
  double radius = 0.0;
};

// One id per distinct vertex position (ids 0, 1, ... in the order of the positions), so that
// duplicated seam vertices weld.
[[nodiscard]] std::vector<std::uint32_t> weldedVertexIds(const Mesh& mesh);

// True when every edge is shared by exactly two triangles that run along it in opposite
// directions. Vertices at the same position count as one (meshes may duplicate seam vertices);
// triangles that collapse to an edge or a point are ignored.
[[nodiscard]] bool isClosedMesh(const Mesh& mesh);

// Positive for a closed mesh whose triangles wind counter-clockwise seen from outside.
[[nodiscard]] double signedVolume(const Mesh& mesh);

// Centred on the bounding-box centre: not minimal, but cheap, deterministic and within
// sqrt(3)/2 of the box diagonal, which is all placement and a proxy need.
[[nodiscard]] BoundingSphere boundingSphere(const Mesh& mesh);

}  // namespace cdb
