#include "scenes/PlacementCapacity.h"

#include <numbers>

namespace cdb {

double boundingRadius(const MeshSpec& mesh) {
  switch (mesh.kind) {
    case MeshSpec::Kind::Torus:
      return mesh.majorRadius + mesh.minorRadius;
    case MeshSpec::Kind::Plane:
      return mesh.planeSize * std::numbers::sqrt2 / 2;
    case MeshSpec::Kind::Asset:
      return mesh.assetSize * std::numbers::sqrt3 / 2;
  }
  return 0;
}

double placementFill(const BodyGroup& body, int count) {
  const RandomPlacement& p = *body.placement;
  const double rr = boundingRadius(body.mesh) + p.minGap / 2;
  double volume = 1;
  for (int i = 0; i < 3; ++i) volume *= p.regionMax[i] - p.regionMin[i] + 2 * rr;
  return count * 4.0 / 3.0 * std::numbers::pi * rr * rr * rr / volume;
}

}  // namespace cdb
