#include "scenes/SceneGeometry.h"

#include <string>

#include "core/Errors.h"

namespace cdb {

void checkSceneIndices(const SceneGeometry& scene) {
  for (const SceneObject& o : scene.objects)
    if (o.mesh >= scene.meshes.size())
      throw InputError("scene object uses mesh " + std::to_string(o.mesh) + " of " +
                       std::to_string(scene.meshes.size()));
  for (const Mesh& m : scene.meshes)
    for (const Triangle& t : m.triangles)
      for (std::uint32_t i : t)
        if (i >= m.vertices.size())
          throw InputError("mesh '" + m.name + "' has a triangle index " + std::to_string(i) +
                           " beyond its " + std::to_string(m.vertices.size()) + " vertices");
}

}  // namespace cdb
