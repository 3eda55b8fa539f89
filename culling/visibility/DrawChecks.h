#pragma once
// The argument checks a recording backend (cpu, gl-compute) makes of each draw and pose upload,
// with their one-line RunErrors: the object is in the attached scene (`scene` may be null: none
// attached), a pass is open, the triangles are the object's.
#include <cstddef>
#include <cstdint>
#include <span>

#include "culling/visibility/VisibilityBackend.h"

namespace cdb {

void checkObjectDrawn(const SceneGeometry* scene, ObjectId object, bool inPass);
void checkRangeDrawn(const SceneGeometry* scene, const MeshRange& range, bool inPass);
void checkListedDrawn(const SceneGeometry* scene, ObjectId object,
                      std::span<const std::uint32_t> triangles, bool inPass);
// One pose per object of the attached scene.
void checkPoseCount(const SceneGeometry* scene, std::size_t poses);

}  // namespace cdb
