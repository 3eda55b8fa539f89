#pragma once
// Scenes of axis-aligned boxes for the strategy tests: each object is its own 12-triangle box
// mesh centred at its origin, placed by a translation, so a test states world boxes directly
// and the projected intervals [Min, Max] on each axis are exactly the boxes' sides.
#include <random>
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

// `count` boxes with centres uniform in [0, span)^3 and half sides uniform in [0.2, 0.8), drawn
// from `rng` (centre, then half sides, box after box): dense enough that many touch.
inline std::vector<Aabb> randomBoxes(std::mt19937_64& rng, int count, double span) {
  std::uniform_real_distribution<double> centre(0.0, span), half(0.2, 0.8);
  std::vector<Aabb> boxes;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d c(centre(rng), centre(rng), centre(rng));
    const Eigen::Vector3d h(half(rng), half(rng), half(rng));
    boxes.emplace_back(c - h, c + h);
  }
  return boxes;
}

inline Aabb box(double x0, double x1, double y0, double y1, double z0, double z1) {
  return Aabb(Eigen::Vector3d(x0, y0, z0), Eigen::Vector3d(x1, y1, z1));
}

}  // namespace cdb::testing
