#pragma once
// Issues every kind of draw the strategies use (queries and writes of mesh ranges, triangle lists
// and boxes, single and batched, in each depth mode) once at a resolution, so that shader compilation and
// framebuffer allocation happen before the first timed frame rather than inside it.
#include <span>

#include "core/Pose.h"
#include "culling/visibility/VisibilityBackend.h"
#include "scenes/SceneGeometry.h"

namespace cdb {

void warmUpBackend(VisibilityBackend& backend, const SceneGeometry& scene,
                   std::span<const Pose> poses, int resolution);

}  // namespace cdb
