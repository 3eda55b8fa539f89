#pragma once
// A closed sphere mesh of rings x segments, for tests that need closed meshes of their own shape.
#include <Eigen/Core>
#include <cstdint>
#include <numbers>

#include "scenes/Mesh.h"

namespace cdb::test {

// A sphere of `rings` x `segments` quads (two triangles each, caps of triangles), wound
// counter-clockwise seen from outside where the vertices lie around the origin as on a sphere:
// vertexAt(theta, phi) gives each vertex at polar angle theta and azimuth phi, asked in order:
// the north pole (0, 0), rings 1 .. rings - 1 (theta = pi r / rings, phi = 2 pi s / segments),
// the south pole (pi, 0).
template <class VertexAt>
Mesh ringSphere(int rings, int segments, VertexAt&& vertexAt) {
  Mesh m;
  m.vertices.push_back(vertexAt(0.0, 0.0));
  for (int r = 1; r < rings; ++r) {
    const double theta = std::numbers::pi * r / rings;
    for (int s = 0; s < segments; ++s)
      m.vertices.push_back(vertexAt(theta, 2 * std::numbers::pi * s / segments));
  }
  m.vertices.push_back(vertexAt(std::numbers::pi, 0.0));
  const auto at = [&](int ring, int s) {  // ring 1 .. rings - 1
    return static_cast<std::uint32_t>(1 + (ring - 1) * segments + (s % segments));
  };
  const auto south = static_cast<std::uint32_t>(m.vertices.size() - 1);
  for (int s = 0; s < segments; ++s) {
    m.triangles.push_back({0, at(1, s), at(1, s + 1)});
    for (int r = 1; r + 1 < rings; ++r) {
      m.triangles.push_back({at(r, s), at(r + 1, s), at(r + 1, s + 1)});
      m.triangles.push_back({at(r, s), at(r + 1, s + 1), at(r, s + 1)});
    }
    m.triangles.push_back({at(rings - 1, s), south, at(rings - 1, s + 1)});
  }
  return m;
}

}  // namespace cdb::test
