#pragma once
// Closed box meshes for the tests of the facing rule (a closed mesh drawn whole draws only the
// faces that decide it): a box wound either way, and several meshes joined into one.
#include <Eigen/Core>
#include <vector>

#include "scenes/Mesh.h"

namespace cdb::test {

// The box of half size `half` centred on `centre`, 12 triangles wound counter-clockwise seen from
// outside (`outward`) or clockwise (its signed volume then negative).
inline Mesh boxMeshAt(const Eigen::Vector3f& centre, const Eigen::Vector3f& half, bool outward) {
  Mesh m;
  m.name = outward ? "box" : "inverted box";
  for (int i = 0; i < 8; ++i)
    m.vertices.push_back(centre + Eigen::Vector3f((i & 1) ? half.x() : -half.x(),
                                                  (i & 2) ? half.y() : -half.y(),
                                                  (i & 4) ? half.z() : -half.z()));
  // Counter-clockwise seen from outside; vertex index bits are (x, y, z).
  m.triangles = {{0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5},   // x = -, x = +
                 {0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3},   // y = -, y = +
                 {0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}};  // z = -, z = +
  if (!outward)
    for (auto& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

// The meshes' vertices and triangles in one mesh.
inline Mesh joinedMeshes(const std::vector<Mesh>& parts) {
  Mesh m;
  m.name = "joined";
  for (const Mesh& p : parts) {
    const auto base = static_cast<std::uint32_t>(m.vertices.size());
    m.vertices.insert(m.vertices.end(), p.vertices.begin(), p.vertices.end());
    for (const auto& t : p.triangles)
      m.triangles.push_back({base + t[0], base + t[1], base + t[2]});
  }
  return m;
}

// The tests' closed mesh wound both ways: a box of half size 1 at (5, 0, 0) wound outward and one
// of half size 0.6 at the origin wound inward (closed, positive volume, winding number -1 inside
// the small box); with `smallInward` false, both wound outward (a solid).
inline Mesh boxesWoundBothWays(bool smallInward = true) {
  return joinedMeshes({boxMeshAt({5, 0, 0}, {1, 1, 1}, true),
                       boxMeshAt({0, 0, 0}, {0.6f, 0.6f, 0.6f}, !smallInward)});
}

}  // namespace cdb::test
