#pragma once
// What culling and exact tests see of a scene: meshes, and which mesh each object uses.
// Poses change per frame and travel separately (std::span<const Pose>, one per object).
#include <cstdint>
#include <string>
#include <vector>

#include "scenes/Mesh.h"

namespace cdb {

using ObjectId = std::uint32_t;

struct SceneObject {
  std::uint32_t mesh = 0;  // index into SceneGeometry::meshes
  bool fixed = false;      // static in the dynamics (planes); still takes part in collision detection
  std::string group;       // body group of the config it came from
};

struct SceneGeometry {
  std::vector<Mesh> meshes;
  std::vector<SceneObject> objects;

  [[nodiscard]] const Mesh& meshOf(ObjectId object) const { return meshes[objects[object].mesh]; }
  [[nodiscard]] std::size_t objectCount() const { return objects.size(); }
};

// Throws InputError when an object names a mesh the scene does not have or a triangle a vertex its
// mesh does not have: what every backend and renderer checks before it indexes them.
void checkSceneIndices(const SceneGeometry& scene);

}  // namespace cdb
