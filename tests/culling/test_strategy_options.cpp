// A config's strategy options reach the strategies: the YAML's culling section, loaded, handed to
// the registry's factories, decides the view axes and the OBB trees the strategies use.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "BoxScenes.h"
#include "culling/DetectorRegistry.h"
#include "culling/bvh/SceneHierarchies.h"
#include "culling/strategies/CollisionIndependentSets.h"
#include "culling/strategies/HierarchicalCollisionIndependentSets.h"
#include "culling/visibility/ScriptedVisibilityOracle.h"
#include "scenes/ConfigLoader.h"

namespace cdb {
namespace {

ScenarioConfig configWithCulling(const std::string& culling) {
  return loadScenarioConfigFromText(
      "environment: test\n"
      "bodies:\n"
      "  - {name: a, mesh: {kind: torus}, count: 2, "
      "placement: {region_min: [-5, -5, -5], region_max: [5, 5, 5]}}\n"
      "culling:\n" +
          culling,
      "options.yaml");
}

// Five boxes spread along y, overlapping in x and z: left to choose, both strategies look along y.
testing::BoxScene spreadAlongY() {
  std::vector<Aabb> boxes;
  for (int i = 0; i < 5; ++i)
    boxes.push_back(testing::box(0.25 * i, 1 + 0.25 * i, 3 * i, 3 * i + 1, 0, 1));
  return testing::boxScene(boxes);
}

template <class Strategy>
Strategy& created(std::unique_ptr<CullingStrategy>& owned) {
  auto* strategy = dynamic_cast<Strategy*>(owned.get());
  EXPECT_NE(strategy, nullptr);
  return *strategy;
}

TEST(DetectorOptions, CisAxisFromTheConfigReachesTheStrategy) {
  auto s = spreadAlongY();
  for (const auto& [word, axis] : {std::pair<std::string, int>{"x", 0}, {"z", 2}, {"auto", 1}}) {
    const ScenarioConfig config = configWithCulling("  strategies: {cis: {axis: " + word + "}}\n");
    auto owned = DetectorRegistry::builtin().create("cis", DetectorOptions{64, config.culling});
    auto& cis = created<CollisionIndependentSets>(owned);
    ScriptedVisibilityOracle oracle([](const VisibilityCall&, auto) { return true; });
    cis.attach(s.scene, oracle);
    (void)cis.cull({s.poses, 0});
    EXPECT_EQ(cis.lastFrame().axis, axis) << word;
  }
}

TEST(DetectorOptions, OursFirstAxisFromTheConfigReachesTheStrategy) {
  auto s = spreadAlongY();
  for (const auto& [word, axis] : {std::pair<std::string, int>{"x", 0}, {"z", 2}, {"auto", 1}}) {
    const ScenarioConfig config =
        configWithCulling("  strategies: {ours: {first_axis: " + word + "}}\n");
    auto owned = DetectorRegistry::builtin().create("ours", DetectorOptions{64, config.culling});
    auto& ours = created<HierarchicalCollisionIndependentSets>(owned);
    // Nothing fully visible: a set survives to the leaves, over several levels, unless the boxes
    // lie apart along the first axis (y) and level 0 leaves no set.
    ScriptedVisibilityOracle oracle([](const VisibilityCall&, auto) { return false; });
    ours.attach(s.scene, oracle);
    (void)ours.cull({s.poses, 0});
    const std::vector<int>& axes = ours.lastFrame().axes;
    ASSERT_GE(axes.size(), axis == 1 ? 1u : 2u) << word;
    EXPECT_EQ(axes[0], axis) << word;
    if (axes.size() > 1) {
      EXPECT_EQ(axes[1], (axis + 1) % 3) << word;
    }
  }
}

// The trees the strategies attach with are those of the options the config gives each: built
// beforehand under exactly these options, attaching builds none. The boxes are of a size no other
// test uses, so that no tree of theirs under other options is in the process-wide cache either.
TEST(DetectorOptions, EachHierarchyStrategyBuildsItsTreesUnderItsConfiguredOptions) {
  auto s = testing::boxScene({testing::box(0, 1.37, 0, 1.41, 0, 1.43),
                              testing::box(1, 2.37, 0, 1.41, 0, 1.43)});
  const ScenarioConfig config = configWithCulling(
      "  hierarchy: {branching: 2, leaf_triangles: 3, offset: 0.004}\n"
      "  strategies: {ours: {hierarchy: {leaf_triangles: 5}}}\n");
  const HierarchySpec bvh{.branching = 2, .leafTriangles = 3, .offset = 0.004};
  const HierarchySpec ours{.branching = 2, .leafTriangles = 5, .offset = 0.004};
  for (const Mesh& mesh : s.scene.meshes) {
    (void)cachedHierarchy(mesh, hierarchyOptions(mesh, bvh));
    (void)cachedHierarchy(mesh, hierarchyOptions(mesh, ours));
  }
  const std::uint64_t before = obbTreeBuilds();
  ScriptedVisibilityOracle oracle([](const VisibilityCall&, auto) { return false; });
  for (const char* name : {"cullide_bvh", "ours"}) {
    auto strategy = DetectorRegistry::builtin().create(name, DetectorOptions{64, config.culling});
    strategy->attach(s.scene, oracle);
    EXPECT_EQ(obbTreeBuilds(), before) << name << " built a tree under other options";
  }
}

}  // namespace
}  // namespace cdb
