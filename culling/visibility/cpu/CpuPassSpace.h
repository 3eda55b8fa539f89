#pragma once
// The screen space of a pass as the CPU-side backends (cpu, gl-compute) set it up: the pass'
// rasterisation parameters, the matrix from world to (x pixels, y pixels, depth key), a point
// carried into it with the rounding both backends reproduce, and the winding of a closed mesh.
// One definition, so that the two backends' answers can be equal bit for bit.
#include <cstdint>

#include "culling/visibility/DepthPassSetup.h"
#include "culling/visibility/VisibilityBackend.h"
#include "culling/visibility/cpu/CpuRecording.h"
#include "culling/visibility/cpu/CpuTriangleSetup.h"

namespace cdb {

// The rasterisation parameters of a pass set up as `setup` with `options`.
[[nodiscard]] RasterPass rasterPassOf(const DepthPassSetup& setup, const VisibilityOptions& options,
                                      bool orderIndependent);

// World -> (x, y, key): key = sign * stored depth = sign * (near + t (far - near)).
[[nodiscard]] ScreenMatrix worldToKeyOf(const DepthPassSetup& setup);

// m * (x, y, z, 1) in double, each operation rounded as written: rows x and y summed from the
// left, the key row's last two products first (the order Eigen's product of a 3x3 block and a
// vector gave before this function existed; the gl-compute shaders write the same).
struct ScreenPoint {
  double x, y, k;
};
[[nodiscard]] inline ScreenPoint screenPoint(const ScreenMatrix& m, double x, double y, double z) {
  return {((m(0, 0) * x + m(0, 1) * y) + m(0, 2) * z) + m(0, 3),
          ((m(1, 0) * x + m(1, 1) * y) + m(1, 2) * z) + m(1, 3),
          (m(2, 0) * x + (m(2, 1) * y + m(2, 2) * z)) + m(2, 3)};
}

// CpuCommand::winding of the mesh's whole draws: solidWinding, +1 when its winding number is shown
// never negative (a solid wound counter-clockwise seen from outside), -1 never positive, else 0.
[[nodiscard]] std::int8_t meshWinding(const Mesh& mesh);

}  // namespace cdb
