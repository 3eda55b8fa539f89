#pragma once
// The thesis' procedural meshes (Chapter 4).
#include "scenes/Mesh.h"

namespace cdb {

// Torus around the local y axis: a rings x sides grid of quads, two triangles each
// (20 x 20 = 800 triangles).
[[nodiscard]] Mesh makeTorus(double majorRadius, double minorRadius, int rings, int sides);

// Square plane in the local x-z plane centred at the origin, normal +y: a cells x cells grid,
// two triangles a cell (30 x 30 = 1,800 triangles).
[[nodiscard]] Mesh makePlane(double size, int cells);

}  // namespace cdb
