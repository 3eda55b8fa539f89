#include "harness/measure/BackendWarmUp.h"

#include <algorithm>
#include <vector>

#include "core/Aabb.h"
#include "culling/visibility/VisibilityBackendRegistry.h"

namespace cdb {

void warmUpBackend(VisibilityBackend& backend, const SceneGeometry& scene,
                   std::span<const Pose> poses, int resolution) {
  if (scene.objectCount() == 0) return;
  backend.setPoses(poses);
  Aabb bounds;
  for (ObjectId o = 0; o < scene.objectCount(); ++o)
    bounds.extend(transformAabb(scene.meshOf(o).bounds(), poses[o]));
  OrientedBox box;
  box.halfExtents = scene.meshOf(0).bounds().sizes() * 0.5;
  box.center = scene.meshOf(0).bounds().center();
  const std::uint32_t triangles = static_cast<std::uint32_t>(scene.meshOf(0).triangleCount());
  const std::vector<std::uint32_t> some = {0, triangles / 2};
  std::vector<std::uint8_t> answers;
  std::vector<DepthUse> uses = {DepthUse::Fresh, DepthUse::SharedFirst, DepthUse::SharedSecond};
  if (backend.supportsOrderIndependent()) uses.push_back(DepthUse::OrderIndependent);
  const auto writes = [&] {
    backend.writeRange({0, 0, triangles});
    backend.writeTriangles(0, some);
    backend.writeBox(0, box);
    backend.writeBoxes(0, std::span<const OrientedBox>(&box, 1));
  };
  const auto tests = [&] {
    (void)backend.queryRange({0, 0, triangles});
    (void)backend.queryRange({0, 0, 1});
    (void)backend.queryBox(0, box);
    (void)backend.queryTriangles({0, 0, std::min<std::uint32_t>(triangles, 2)});
    (void)backend.queryTriangles(0, some);
    (void)backend.queryBoxes(0, std::span<const OrientedBox>(&box, 1));
  };
  for (DepthUse use : uses) {
    backend.beginPass({Eigen::Vector3d::UnitX(), bounds, resolution}, use);
    // Tests after writes in every kind of pass; before them too where the pass allows it.
    if (use != DepthUse::OrderIndependent) tests();
    writes();
    tests();
  }
  backend.fetchResults(answers);
}

std::unique_ptr<VisibilityBackend> warmedUpBackend(BackendResources& resources,
                                                   const std::string& backend,
                                                   const CullingSpec& culling,
                                                   const SceneGeometry& scene,
                                                   std::span<const Pose> poses, int resolution) {
  auto created =
      VisibilityBackendRegistry::builtin().create(backend, resources, visibilityOptionsOf(culling));
  created->attachScene(scene);
  warmUpBackend(*created, scene, poses, resolution);
  return created;
}

}  // namespace cdb
