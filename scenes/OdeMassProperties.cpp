#include "scenes/OdeMassProperties.h"

#include <cmath>
#include <string>

#include "core/Errors.h"
#include "scenes/MeshMeasures.h"

namespace cdb {

namespace {

bool isUsable(const dMass& m) {
  if (!(std::isfinite(m.mass) && m.mass > 0)) return false;
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(m.c[i])) return false;
  }
  // Principal moments of a real body are positive; the diagonal is a cheap necessary check.
  return m.I[0] > 0 && m.I[5] > 0 && m.I[10] > 0 && std::isfinite(m.I[0] + m.I[5] + m.I[10]);
}

dMass massFromTrimesh(dTriMeshDataID meshData, double density) {
  // dMassSetTrimesh reads the triangles through a geom; a temporary one outside any space does.
  dGeomID geom = dCreateTriMesh(nullptr, meshData, nullptr, nullptr, nullptr);
  dMass m;
  dMassSetTrimesh(&m, density, geom);
  dGeomDestroy(geom);
  return m;
}

// Zero mass (unusable) for a shape without volume; ODE would only complain about it.
dMass massFromProxy(const Mesh& mesh, double density, CollisionProxy proxy) {
  dMass m;
  dMassSetZero(&m);
  if (proxy == CollisionProxy::Sphere) {
    const BoundingSphere sphere = boundingSphere(mesh);
    if (!(sphere.radius > 0)) return m;
    dMassSetSphere(&m, density, sphere.radius);
    dMassTranslate(&m, sphere.centre.x(), sphere.centre.y(), sphere.centre.z());
  } else {
    const auto box = mesh.bounds();
    const Eigen::Vector3d size = box.sizes();
    if (!(size.minCoeff() > 0)) return m;
    dMassSetBox(&m, density, size.x(), size.y(), size.z());
    dMassTranslate(&m, box.center().x(), box.center().y(), box.center().z());
  }
  return m;
}

}  // namespace

BodyMass bodyMass(const Mesh& mesh, dTriMeshDataID meshData, double density, CollisionProxy proxy,
                  std::string_view group) {
  if (!(std::isfinite(density) && density > 0)) {
    throw InputError("group " + std::string(group) + ": density must be > 0, got " +
                     std::to_string(density));
  }
  BodyMass result;
  dMass m{};
  if (meshData && isClosedMesh(mesh) && signedVolume(mesh) > 0) {
    m = massFromTrimesh(meshData, density);
    result.fromMesh = isUsable(m);
  }
  if (!result.fromMesh) {
    if (mesh.bounds().isEmpty()) {
      throw InputError("group " + std::string(group) + ": mesh " + mesh.name + " has no vertices");
    }
    m = massFromProxy(mesh, density, proxy);
  }
  if (!isUsable(m)) {
    throw InputError("group " + std::string(group) + ": mesh " + mesh.name +
                     " encloses no volume, so a moving body of it has no mass: make the group "
                     "fixed or give it a solid mesh");
  }
  result.centre = Eigen::Vector3d(m.c[0], m.c[1], m.c[2]);
  dMassTranslate(&m, -m.c[0], -m.c[1], -m.c[2]);
  result.mass = m;
  return result;
}

}  // namespace cdb
