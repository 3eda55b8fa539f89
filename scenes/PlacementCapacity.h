#pragma once
// How full random placement would make a body group's region, so that a count it cannot hold is
// refused as input (by the config loader and for a swept count) instead of failing to place.
#include "scenes/ScenarioConfig.h"

namespace cdb {

// Radius of a sphere about the local origin that holds the whole mesh. Assets are normalised to a
// longest side of assetSize, so half the diagonal of that cube bounds them whatever their shape.
[[nodiscard]] double boundingRadius(const MeshSpec& mesh);

// The fraction of the group's placement region, grown by a bounding radius plus half the gap on
// every side, that `count` bounding spheres (radius plus half the gap) fill. At most
// limits::kMaxPlacementFill is accepted. `body` must have a placement.
[[nodiscard]] double placementFill(const BodyGroup& body, int count);

}  // namespace cdb
