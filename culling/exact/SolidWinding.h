#pragma once
// Which side of a closed mesh is solid, where that can be shown: the sign its winding number never
// leaves. A backend drawing a whole mesh may then draw only the faces that decide it
// (CpuCommand::winding): along a line of sight, where the winding number is never negative (faces
// wound counter-clockwise seen from outside), the first face crossed enters the solid, so it is
// turned toward the viewer, and the last one leaves it, turned away. A closed mesh alone does not
// give that: a part wound inward beside one wound outward, or a surface pushed through itself, has
// points of winding number -1, where the nearest face is one turned away.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>

#include "scenes/Mesh.h"

namespace cdb {

// +1 when the mesh's winding number is 0 or more at every point off it, -1 when it is 0 or less;
// shown from three facts: the mesh is closed (isClosedMesh), no two of its triangles meet other
// than at the corners and the edge they share (exact predicates), and every part of it (triangles
// joined across edges) encloses a volume of the same sign. Then each part is a surface that bounds
// one region, of winding number +1 (or -1) for that part, and the mesh's winding number at a point
// is the sum over the parts enclosing it. 0 when any fact fails, also for meshes of which the sign
// holds but is not shown this way: a hollow shell (its inner surface winds the other way), two
// parts that overlap, a collapsed triangle.
[[nodiscard]] int solidWinding(const Mesh& mesh);

// solidWinding, answered again without the check for a mesh bit for bit like one of the last
// 1,024 asked (64 MiB of copies at most; a backend attaches the same meshes for every cell of a
// run, and tests attach them hundreds of times). Thread-safe.
[[nodiscard]] int rememberedSolidWinding(const Mesh& mesh);

// Whether two triangles, given by their corners' indices into `at` (a corner they share has one
// index), meet nowhere but at the corners and the edge they share: exactly, except that two
// triangles of the same corners, and a collapsed triangle sharing a corner in the other's plane,
// are answered false.
[[nodiscard]] bool meetOnlyWhereShared(const std::array<std::uint32_t, 3>& a,
                                       const std::array<std::uint32_t, 3>& b,
                                       std::span<const Eigen::Vector3d> at);

}  // namespace cdb
