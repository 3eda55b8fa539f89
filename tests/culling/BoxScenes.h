#pragma once
// Scenes of axis-aligned boxes for the strategy tests: each object is its own 12-triangle box
// mesh centred at its origin, placed by a translation, so a test states world boxes directly
// and the projected intervals [Min, Max] on each axis are exactly the boxes' sides.
#include <vector>

#include "core/Aabb.h"
#include "core/Pose.h"
#include "scenes/SceneGeometry.h"

namespace cdb::testing {

inline Mesh boxMesh(const Eigen::Vector3d& halfSize) {
  Mesh m;
  m.name = "box";
  for (int i = 0; i < 8; ++i)
    m.vertices.emplace_back(((i & 1) ? 1.0f : -1.0f) * static_cast<float>(halfSize.x()),
                            ((i & 2) ? 1.0f : -1.0f) * static_cast<float>(halfSize.y()),
                            ((i & 4) ? 1.0f : -1.0f) * static_cast<float>(halfSize.z()));
  // Two triangles per face; vertex index bits are (x, y, z).
  m.triangles = {{0, 2, 6}, {0, 6, 4}, {1, 5, 7}, {1, 7, 3},   // x = -, x = +
                 {0, 4, 5}, {0, 5, 1}, {2, 3, 7}, {2, 7, 6},   // y = -, y = +
                 {0, 1, 3}, {0, 3, 2}, {4, 6, 7}, {4, 7, 5}};  // z = -, z = +
  return m;
}

struct BoxScene {
  SceneGeometry scene;
  std::vector<Pose> poses;
};

// The meshes are in float: tests keep gaps between boxes well above float rounding.
inline BoxScene boxScene(const std::vector<Aabb>& boxes) {
  BoxScene s;
  for (const auto& b : boxes) {
    s.scene.objects.push_back({static_cast<std::uint32_t>(s.scene.meshes.size()), false, "box"});
    s.scene.meshes.push_back(boxMesh(b.sizes() / 2));
    Pose p;
    p.translation = b.center();
    s.poses.push_back(p);
  }
  return s;
}

inline Aabb box(double x0, double x1, double y0, double y1, double z0, double z1) {
  return Aabb(Eigen::Vector3d(x0, y0, z0), Eigen::Vector3d(x1, y1, z1));
}

}  // namespace cdb::testing
