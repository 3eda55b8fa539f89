#include "scenes/SceneBuilder.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/Errors.h"
#include "scenes/AssetPath.h"
#include "scenes/ConfigLimits.h"
#include "scenes/MeshLoader.h"
#include "scenes/PlacementCapacity.h"
#include "scenes/ProceduralMeshes.h"

namespace cdb {
namespace {

Mesh makeMesh(const BodyGroup& group, const std::vector<std::string>& assetDirs) {
  const MeshSpec& spec = group.mesh;
  Mesh mesh;
  switch (spec.kind) {
    case MeshSpec::Kind::Torus:
      mesh = makeTorus(spec.majorRadius, spec.minorRadius, spec.rings, spec.sides);
      break;
    case MeshSpec::Kind::Plane:
      mesh = makePlane(spec.planeSize, spec.planeCells);
      break;
    case MeshSpec::Kind::Asset: {
      const std::filesystem::path file = resolveAsset(spec.asset, assetDirs);
      mesh = loadMesh(file, {spec.maxTriangles}).mesh;
      normaliseMesh(mesh, spec.assetSize);
      mesh.source = file.string();
      break;
    }
  }
  mesh.name = group.name;
  return mesh;
}

}  // namespace

SceneGeometry buildScene(const ScenarioConfig& config, const std::vector<std::string>& assetDirs) {
  SceneGeometry scene;
  scene.meshes.reserve(config.bodies.size());
  for (const BodyGroup& group : config.bodies) {
    const auto meshIndex = std::uint32_t(scene.meshes.size());
    scene.meshes.push_back(makeMesh(group, assetDirs));
    for (int i = 0; i < group.count; ++i) {
      scene.objects.push_back(SceneObject{meshIndex, group.fixed, group.name});
    }
  }
  return scene;
}

ScenarioConfig withObjectCount(const ScenarioConfig& config, int count) {
  const std::string& group = config.sweep.countedGroup;
  if (group.empty()) {
    throw InputError(config.sourcePath +
                     ": sweep.counted_group: expected a body group to set the " +
                     "object count of, got none");
  }
  if (count < limits::kObjectCount.min || count > limits::kObjectCount.max) {
    throw InputError(config.sourcePath + ": object count of '" + group +
                     "': expected an integer in [" + std::to_string(limits::kObjectCount.min) +
                     ", " + std::to_string(limits::kObjectCount.max) + "], got " +
                     std::to_string(count));
  }
  ScenarioConfig out = config;
  const auto it = std::find_if(out.bodies.begin(), out.bodies.end(),
                               [&](const BodyGroup& b) { return b.name == group; });
  if (it == out.bodies.end()) {
    throw InputError(config.sourcePath +
                     ": sweep.counted_group: expected the name of a body group, got '" + group +
                     "'");
  }
  if (!it->poses.empty()) {
    throw InputError(config.sourcePath + ": sweep.counted_group: expected a group with random " +
                     "placement, got '" + group + "' with explicit poses");
  }
  // The loader checked the config's own counts; a count from the command line is checked here, so
  // that it is refused as input rather than failing to place bodies after the run has begun.
  if (const double fill = it->placement ? placementFill(*it, count) : 0.0;
      fill > limits::kMaxPlacementFill) {
    throw InputError(config.sourcePath + ": object count " + std::to_string(count) + " of '" +
                     group + "': expected a count whose bounding spheres fill at most " +
                     std::to_string(int(limits::kMaxPlacementFill * 100)) +
                     "% of its placement region (random placement jams), got " +
                     std::to_string(std::llround(100 * fill)) + "%");
  }
  it->count = count;
  return out;
}

}  // namespace cdb
