#pragma once
// One cell measured: its detector created, attached and the backend warmed up at the cell's
// resolution (none of it CD time), then every measured frame of the cell's simulation detected,
// timed and compared with the ground truth, one frames.csv row each.
#include <functional>
#include <string>
#include <vector>

#include "culling/CollisionDetector.h"
#include "culling/DetectorRegistry.h"
#include "culling/visibility/VisibilityBackend.h"
#include "harness/run/CellFrames.h"
#include "harness/run/RunPlan.h"
#include "harness/run/WallTimeBreakdown.h"
#include "harness/tables/FrameRecord.h"

namespace cdb {

// `frames` must hold the cell's scene and frames (CellFrames::prepare); `afterEachFrame` runs after
// every row (progress, and stopping between frames by throwing).
[[nodiscard]] std::vector<FrameRecord> measureCell(const Cell& cell, CellFrames& frames,
                                                   DetectorOptions options,
                                                   VisibilityBackend& backend,
                                                   WallTimeBreakdown& time,
                                                   const std::function<void()>& afterEachFrame);

}  // namespace cdb
