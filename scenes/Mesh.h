#pragma once
// A triangle mesh in its local frame. Triangles index into vertices.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace cdb {

using Triangle = std::array<std::uint32_t, 3>;

struct Mesh {
  std::string name;
  std::string source;  // the file it was loaded from (empty: made here)
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Triangle> triangles;

  [[nodiscard]] std::size_t triangleCount() const { return triangles.size(); }
  [[nodiscard]] Eigen::AlignedBox3d bounds() const {
    Eigen::AlignedBox3d box;
    for (const auto& v : vertices) box.extend(v.cast<double>());
    return box;
  }
};

}  // namespace cdb
