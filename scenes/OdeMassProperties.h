#pragma once
// Mass properties of a moving body in the form ODE requires: ODE bodies must have their centre of
// mass at the body origin, so the mass comes back translated there, with the centre (in mesh-local
// coordinates) that the caller offsets the geom and the pose by.
#include <string_view>

#include <Eigen/Core>
#include <ode/ode.h>

#include "scenes/Mesh.h"
#include "scenes/ScenarioConfig.h"

namespace cdb {

struct BodyMass {
  dMass mass{};                                      // centred: mass.c is zero
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // centre of mass, mesh-local
  bool fromMesh = false;  // false: the mesh is open or inside out, so the proxy's shape was used
};

// From the closed mesh (dMassSetTrimesh over `meshData`, `density`) when it encloses a positive
// volume; otherwise from the proxy: the bounding sphere for Sphere, the bounding box for Box and
// Trimesh. Throws InputError naming `group` when neither has a volume (a flat mesh cannot move).
[[nodiscard]] BodyMass bodyMass(const Mesh& mesh, dTriMeshDataID meshData, double density,
                                CollisionProxy proxy, std::string_view group);

}  // namespace cdb
