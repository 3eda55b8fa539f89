// bvh_build/<mesh>/<env>: one build of a mesh's 8-ary OBB tree (thesis 3.4.1, ObbTree::build)
// under the tree options an environment's config gives ours (hierarchyOptions: leaf size, offset),
// the one-off cost a strategy with a hierarchy pays per mesh (runs share trees: cachedHierarchy).
// The meshes come from the configs without simulating anything: the torus under env1 (leaves of
// up to 8 triangles) and env3 (16), the plane under env1 (env2's planes are the same), the dragon
// under env2.
#include <string>

#include "bench/BenchmarkSuite.h"
#include "core/Errors.h"
#include "culling/bvh/SceneHierarchies.h"

namespace cdb::bench {

namespace {

struct MeshOfEnvironment {
  const char* mesh;         // the name in the benchmark's name
  const char* environment;  // whose config gives the mesh and the tree options
  const char* group;        // the body group using the mesh
};

constexpr MeshOfEnvironment kMeshes[] = {{"torus", "env1", "tori"},
                                         {"torus", "env3", "tori"},
                                         {"plane", "env1", "planes"},
                                         {"dragon", "env2", "dragons"}};

const Mesh& meshOfGroup(const SceneGeometry& scene, const std::string& group) {
  for (const SceneObject& o : scene.objects)
    if (o.group == group) return scene.meshes[o.mesh];
  throw InputError("no body group '" + group + "' in the scene");
}

void buildTree(benchmark::State& state, RecordedFrames& frames, const MeshOfEnvironment& m) {
  const RecordedScene& environment = frames.unsimulated(m.environment);
  const Mesh& mesh = meshOfGroup(environment.scene, m.group);
  const ObbTreeOptions options =
      hierarchyOptions(mesh, environment.config.culling.strategies.ours.hierarchy);
  for (auto _ : state) {
    ObbTree tree = ObbTree::build(mesh, options);
    benchmark::DoNotOptimize(tree);
  }
  const ObbTree tree = ObbTree::build(mesh, options);
  std::size_t leaves = 0;
  for (const ObbTreeNode& node : tree.nodes()) leaves += node.leaf() ? 1 : 0;
  state.counters["triangles"] = double(mesh.triangleCount());
  state.counters["nodes"] = double(tree.nodes().size());
  state.counters["levels"] = double(tree.levels());
  state.counters["leaves"] = double(leaves);
  state.counters["leaf_triangles"] = double(options.leafTriangles);
}

}  // namespace

void registerBvhBuildBenchmarks(RecordedFrames& frames) {
  for (const MeshOfEnvironment& m : kMeshes) {
    const std::string name = std::string("bvh_build/") + m.mesh + "/" + m.environment;
    registerMilliseconds(name, [&frames, &m](benchmark::State& state) { buildTree(state, frames, m); });
  }
}

}  // namespace cdb::bench
