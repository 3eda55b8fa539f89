#include "scenes/ProceduralMeshes.h"

#include <cmath>
#include <numbers>
#include <string>

#include "core/Errors.h"

namespace cdb {

Mesh makeTorus(double majorRadius, double minorRadius, int rings, int sides) {
  if (!(majorRadius > 0) || !(minorRadius > 0) || !(minorRadius < majorRadius) || rings < 3 ||
      sides < 3) {
    throw InputError(
        "torus: expected 0 < minor radius < major radius and rings, sides >= 3, got R=" +
        std::to_string(majorRadius) + " r=" + std::to_string(minorRadius) +
        " rings=" + std::to_string(rings) + " sides=" + std::to_string(sides));
  }
  Mesh mesh;
  mesh.name = "torus";
  // One vertex per grid point and indices that wrap around both circles: no seam vertices, so the
  // surface is closed and every edge is shared by exactly two triangles.
  mesh.vertices.reserve(std::size_t(rings) * std::size_t(sides));
  for (int i = 0; i < rings; ++i) {
    const double u = 2.0 * std::numbers::pi * i / rings;
    for (int j = 0; j < sides; ++j) {
      const double v = 2.0 * std::numbers::pi * j / sides;
      const double ring = majorRadius + minorRadius * std::cos(v);
      mesh.vertices.emplace_back(float(ring * std::cos(u)), float(minorRadius * std::sin(v)),
                                 float(ring * std::sin(u)));
    }
  }
  const auto at = [&](int i, int j) { return std::uint32_t((i % rings) * sides + (j % sides)); };
  // dP/du x dP/dv points into the tube, so each quad is wound v-first to face outwards.
  mesh.triangles.reserve(std::size_t(rings) * std::size_t(sides) * 2);
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < sides; ++j) {
      const auto a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      mesh.triangles.push_back({a, d, c});
      mesh.triangles.push_back({a, c, b});
    }
  }
  return mesh;
}

Mesh makePlane(double size, int cells) {
  if (!(size > 0) || !std::isfinite(size) || cells < 1) {
    throw InputError("plane: expected size > 0 and cells >= 1, got size=" + std::to_string(size) +
                     " cells=" + std::to_string(cells));
  }
  Mesh mesh;
  mesh.name = "plane";
  const int n = cells + 1;
  mesh.vertices.reserve(std::size_t(n) * std::size_t(n));
  for (int i = 0; i < n; ++i) {
    const double x = size * (2 * i - cells) / (2.0 * cells);  // exactly symmetric about 0
    for (int j = 0; j < n; ++j) {
      const double z = size * (2 * j - cells) / (2.0 * cells);
      mesh.vertices.emplace_back(float(x), 0.0f, float(z));
    }
  }
  const auto at = [&](int i, int j) { return std::uint32_t(i * n + j); };
  // z x x = +y: winding each quad z-first makes the normal point up.
  mesh.triangles.reserve(std::size_t(cells) * std::size_t(cells) * 2);
  for (int i = 0; i < cells; ++i) {
    for (int j = 0; j < cells; ++j) {
      const auto a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      mesh.triangles.push_back({a, d, c});
      mesh.triangles.push_back({a, c, b});
    }
  }
  return mesh;
}

}  // namespace cdb
