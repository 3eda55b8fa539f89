#pragma once
// Issues every kind of draw the strategies use (queries and writes of mesh ranges, triangle lists
// and boxes, single and batched, in each depth mode) once at a resolution, so that shader compilation and
// framebuffer allocation happen before the first timed frame rather than inside it.
#include <memory>
#include <span>
#include <string>

#include "core/Pose.h"
#include "culling/visibility/BackendResources.h"
#include "culling/visibility/VisibilityBackend.h"
#include "scenes/ScenarioConfig.h"
#include "scenes/SceneGeometry.h"

namespace cdb {

void warmUpBackend(VisibilityBackend& backend, const SceneGeometry& scene,
                   std::span<const Pose> poses, int resolution);

// A new `backend` (a VisibilityBackendRegistry name) with `culling`'s visibility options, attached
// to `scene` and warmed up at `resolution` on `poses`: ready for timed culls.
[[nodiscard]] std::unique_ptr<VisibilityBackend> warmedUpBackend(
    BackendResources& resources, const std::string& backend, const CullingSpec& culling,
    const SceneGeometry& scene, std::span<const Pose> poses, int resolution);

}  // namespace cdb
