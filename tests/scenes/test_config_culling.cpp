// The `culling` section of a scenario config: visibility, the shared hierarchy, and each strategy's
// own options (configs/README.md); good values, their defaults, and one-line errors for bad ones.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "ConfigErrorCheck.h"
#include "ScratchDir.h"
#include "scenes/ConfigLoader.h"

namespace cdb {
namespace {

using test::ConfigErrors;
using test::minimal;
using test::ScratchDir;

ScenarioConfig loadWithCulling(const std::string& culling) {
  ScratchDir dir;
  return loadScenarioConfig(dir.write("culling.yaml", minimal() + "culling:\n" + culling));
}

TEST(CullingConfig, AbsentOptionsKeepTheDocumentedDefaults) {
  const CullingSpec c = loadWithCulling("  strategies: {}\n").culling;
  EXPECT_TRUE(c.visibility.backend.empty());
  EXPECT_TRUE(c.visibility.conservative);
  EXPECT_EQ(c.visibility.rawDepthOffset, 1e-5);
  EXPECT_EQ(c.visibility.threads, 0);
  EXPECT_FALSE(c.strategies.cis.axis.has_value());
  EXPECT_FALSE(c.strategies.ours.firstAxis.has_value());
  for (const HierarchySpec& h : {c.strategies.ours.hierarchy, c.strategies.cullideBvh.hierarchy}) {
    EXPECT_EQ(h.branching, 8);
    EXPECT_EQ(h.leafTriangles, 8);
    EXPECT_EQ(h.offset, 1e-3);
  }
}

TEST(CullingConfig, AxesAreXYZOrAuto) {
  for (const auto& [word, axis] : {std::pair<const char*, AxisChoice>{"x", 0},
                                   {"y", 1},
                                   {"z", 2},
                                   {"auto", std::nullopt}}) {
    const CullingSpec c = loadWithCulling("  strategies:\n    cis: {axis: " + std::string(word) +
                                          "}\n    ours: {first_axis: " + word + "}\n")
                              .culling;
    EXPECT_EQ(c.strategies.cis.axis, axis) << word;
    EXPECT_EQ(c.strategies.ours.firstAxis, axis) << word;
  }
}

TEST(CullingConfig, SharedHierarchyReachesBothHierarchyStrategies) {
  const CullingSpec c =
      loadWithCulling("  hierarchy: {branching: 4, leaf_triangles: 16, offset: 0.002}\n").culling;
  for (const HierarchySpec& h : {c.strategies.ours.hierarchy, c.strategies.cullideBvh.hierarchy}) {
    EXPECT_EQ(h.branching, 4);
    EXPECT_EQ(h.leafTriangles, 16);
    EXPECT_EQ(h.offset, 0.002);
  }
}

TEST(CullingConfig, AStrategysHierarchyOverridesTheSharedOneKeyByKey) {
  const CullingSpec c = loadWithCulling(
                            "  hierarchy: {branching: 4, leaf_triangles: 16, offset: 0.002}\n"
                            "  strategies:\n"
                            "    ours: {hierarchy: {leaf_triangles: 2}}\n")
                            .culling;
  EXPECT_EQ(c.strategies.ours.hierarchy.branching, 4);
  EXPECT_EQ(c.strategies.ours.hierarchy.leafTriangles, 2);
  EXPECT_EQ(c.strategies.ours.hierarchy.offset, 0.002);
  EXPECT_EQ(c.strategies.cullideBvh.hierarchy.leafTriangles, 16);
}

TEST_F(ConfigErrors, CullingUnknownKeyListsTheGroups) {
  expectError(minimal() + "culling:\n  leaf_triangles: 8\n", 5, "culling.leaf_triangles",
              "a known key (one of visibility, hierarchy, strategies), got unknown key "
              "'leaf_triangles'");
}

TEST_F(ConfigErrors, VisibilityIsAMap) {
  expectError(minimal() + "culling:\n  visibility: cpu\n", 5, "culling.visibility",
              "a map with keys backend, conservative, raw_depth_offset, threads, got 'cpu'");
}

TEST_F(ConfigErrors, VisibilityUnknownKey) {
  expectError(minimal() + "culling:\n  visibility: {name: cpu}\n", 5, "culling.visibility.name",
              "one of backend, conservative, raw_depth_offset, threads), got unknown key 'name'");
}

TEST_F(ConfigErrors, VisibilityThreadsOutOfRange) {
  expectError(minimal() + "culling:\n  visibility:\n    threads: -1\n", 6,
              "culling.visibility.threads", "an integer in [0, 1024], got -1");
}

TEST_F(ConfigErrors, BranchingIsTwoFourOrEight) {
  expectError(minimal() + "culling:\n  hierarchy: {branching: 3}\n", 5,
              "culling.hierarchy.branching", "2, 4 or 8, got 3");
  expectError(minimal() + "culling:\n  hierarchy: {branching: 16}\n", 5,
              "culling.hierarchy.branching", "an integer in [2, 8], got 16");
}

TEST_F(ConfigErrors, HierarchyValuesOutOfRange) {
  expectError(minimal() + "culling:\n  hierarchy:\n    leaf_triangles: 0\n", 6,
              "culling.hierarchy.leaf_triangles", "an integer in [1, 1024], got 0");
  expectError(minimal() + "culling:\n  hierarchy:\n    offset: 2\n", 6, "culling.hierarchy.offset",
              "a number in [0, 1], got 2");
}

TEST_F(ConfigErrors, HierarchyUnknownKey) {
  expectError(minimal() + "culling:\n  hierarchy:\n    bvh_offset: 0.001\n", 6,
              "culling.hierarchy.bvh_offset",
              "one of branching, leaf_triangles, offset), got unknown key 'bvh_offset'");
}

TEST_F(ConfigErrors, OptionsOfAStrategyWithoutAnyAreAnError) {
  expectError(minimal() + "culling:\n  strategies:\n    cullide: {}\n", 6,
              "culling.strategies.cullide",
              "a strategy with options (one of cis, cullide_bvh, ours), got unknown key 'cullide'");
}

TEST_F(ConfigErrors, UnknownStrategyOption) {
  expectError(minimal() + "culling:\n  strategies:\n    cis: {first_axis: x}\n", 6,
              "culling.strategies.cis.first_axis",
              "a known key (one of axis), got unknown key 'first_axis'");
  expectError(minimal() + "culling:\n  strategies:\n    ours:\n      axis: x\n", 7,
              "culling.strategies.ours.axis",
              "a known key (one of first_axis, hierarchy), got unknown key 'axis'");
  expectError(minimal() + "culling:\n  strategies:\n    cullide_bvh:\n      leaf_triangles: 4\n", 7,
              "culling.strategies.cullide_bvh.leaf_triangles",
              "a known key (one of hierarchy), got unknown key 'leaf_triangles'");
}

TEST_F(ConfigErrors, AxisIsANameNotANumber) {
  expectError(minimal() + "culling:\n  strategies:\n    cis: {axis: 0}\n", 6,
              "culling.strategies.cis.axis", "x, y, z or auto, got 0");
  expectError(minimal() + "culling:\n  strategies:\n    ours:\n      first_axis: w\n", 7,
              "culling.strategies.ours.first_axis", "x, y, z or auto, got 'w'");
}

TEST_F(ConfigErrors, StrategyHierarchyValueOutOfRange) {
  expectError(
      minimal() + "culling:\n  strategies:\n    ours:\n      hierarchy: {leaf_triangles: 2000}\n",
      7, "culling.strategies.ours.hierarchy.leaf_triangles", "an integer in [1, 1024], got 2000");
}

}  // namespace
}  // namespace cdb
