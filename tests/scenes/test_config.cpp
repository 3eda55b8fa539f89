// Scenario configs: the YAML schema, its one-line errors, the command line's integer lists, the
// shipped environments, and scenes built from configs.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <string_view>

#include "ConfigErrorCheck.h"
#include "ScratchDir.h"
#include "TestAssets.h"
#include "core/Errors.h"
#include "scenes/AssetFiles.h"
#include "scenes/ConfigLoader.h"
#include "scenes/SceneBuilder.h"

namespace cdb {
namespace {

using test::ConfigErrors;
using test::kTori;
using test::minimal;
using test::ScratchDir;

TEST(ConfigLoader, ReadsEveryKey) {
  ScratchDir dir;
  const auto file = dir.write("full.yaml", R"(environment: envX
description: all keys
seed: 18446744073709551615
dynamics:
  gravity: [0.5, -3, 1]
  time_step: 0.002
  steps_per_frame: 3
  frames: 12
  warmup_frames: 4
  container_half_extent: 20
  friction: 0.25
  restitution: 0.5
  max_contacts_per_pair: 4
  linear_damping: 0.01
  angular_damping: 0.02
bodies:
  - name: floor
    mesh: {kind: plane, plane_size: 6, plane_cells: 10}
    fixed: true
    density: 2
    collision: trimesh
    poses:
      - {position: [1, 2, 3], rotation_degrees: [10, 20, 30]}
      - {}
  - name: things
    mesh: {kind: asset, asset: bunny, asset_size: 2.5}
    count: 4
    density: 0.5
    collision: box
    placement:
      region_min: [-10, 0, -10]
      region_max: [10, 5, 10]
      min_gap: 0.1
      random_orientation: false
      speed_min: 0.5
      speed_max: 1.5
      angular_speed_max: 3
  - name: rings
    mesh: {kind: torus, major_radius: 1, minor_radius: 0.1, rings: 12, sides: 6}
    collision: sphere
    placement: {region_min: [-5, -5, -5], region_max: [5, 5, 5]}
sweep:
  resolutions: [256, 512]
  counted_group: rings
  object_counts: {from: 10, to: 30, step: 10}
  repeats: 2
  strategies: [ours, cullide]
culling:
  visibility: {backend: cpu, conservative: false, raw_depth_offset: 0.001, threads: 3}
  hierarchy: {branching: 4, leaf_triangles: 4, offset: 0.01}
  strategies:
    cis: {axis: z}
    cullide_bvh: {hierarchy: {branching: 2, leaf_triangles: 6, offset: 0.02}}
    ours: {first_axis: y, hierarchy: {branching: 8, leaf_triangles: 5, offset: 0.03}}
)");
  const ScenarioConfig c = loadScenarioConfig(file);
  EXPECT_EQ(c.sourcePath, file.string());
  EXPECT_EQ(c.environment, "envX");
  EXPECT_EQ(c.description, "all keys");
  EXPECT_EQ(c.seed, 18446744073709551615ull);
  EXPECT_EQ(c.dynamics.gravity, (Vec3{0.5, -3, 1}));
  EXPECT_EQ(c.dynamics.timeStep, 0.002);
  EXPECT_EQ(c.dynamics.stepsPerFrame, 3);
  EXPECT_EQ(c.dynamics.frames, 12);
  EXPECT_EQ(c.dynamics.warmupFrames, 4);
  EXPECT_EQ(c.dynamics.containerHalfExtent, 20);
  EXPECT_EQ(c.dynamics.friction, 0.25);
  EXPECT_EQ(c.dynamics.restitution, 0.5);
  EXPECT_EQ(c.dynamics.maxContactsPerPair, 4);
  EXPECT_EQ(c.dynamics.linearDamping, 0.01);
  EXPECT_EQ(c.dynamics.angularDamping, 0.02);

  ASSERT_EQ(c.bodies.size(), 3u);
  const BodyGroup& floor = c.bodies[0];
  EXPECT_EQ(floor.name, "floor");
  EXPECT_EQ(floor.mesh.kind, MeshSpec::Kind::Plane);
  EXPECT_EQ(floor.mesh.planeSize, 6);
  EXPECT_EQ(floor.mesh.planeCells, 10);
  EXPECT_EQ(floor.count, 2);  // from the poses
  EXPECT_TRUE(floor.fixed);
  EXPECT_EQ(floor.density, 2);
  EXPECT_EQ(floor.collision, CollisionProxy::Trimesh);
  ASSERT_EQ(floor.poses.size(), 2u);
  EXPECT_EQ(floor.poses[0].position, (Vec3{1, 2, 3}));
  EXPECT_EQ(floor.poses[0].rotationDegrees, (Vec3{10, 20, 30}));
  EXPECT_EQ(floor.poses[1].position, (Vec3{0, 0, 0}));
  EXPECT_FALSE(floor.placement);

  const BodyGroup& things = c.bodies[1];
  EXPECT_EQ(things.mesh.kind, MeshSpec::Kind::Asset);
  EXPECT_EQ(things.mesh.asset, "bunny");
  EXPECT_EQ(things.mesh.assetSize, 2.5);
  EXPECT_EQ(things.count, 4);
  EXPECT_FALSE(things.fixed);
  EXPECT_EQ(things.density, 0.5);
  EXPECT_EQ(things.collision, CollisionProxy::Box);
  ASSERT_TRUE(things.placement);
  EXPECT_EQ(things.placement->regionMin, (Vec3{-10, 0, -10}));
  EXPECT_EQ(things.placement->regionMax, (Vec3{10, 5, 10}));
  EXPECT_EQ(things.placement->minGap, 0.1);
  EXPECT_FALSE(things.placement->randomOrientation);
  EXPECT_EQ(things.placement->speedMin, 0.5);
  EXPECT_EQ(things.placement->speedMax, 1.5);
  EXPECT_EQ(things.placement->angularSpeedMax, 3);

  const BodyGroup& rings = c.bodies[2];
  EXPECT_EQ(rings.mesh.kind, MeshSpec::Kind::Torus);
  EXPECT_EQ(rings.mesh.majorRadius, 1);
  EXPECT_EQ(rings.mesh.minorRadius, 0.1);
  EXPECT_EQ(rings.mesh.rings, 12);
  EXPECT_EQ(rings.mesh.sides, 6);
  EXPECT_EQ(rings.count, 1);
  EXPECT_EQ(rings.collision, CollisionProxy::Sphere);

  EXPECT_EQ(c.sweep.resolutions, (std::vector<int>{256, 512}));
  EXPECT_EQ(c.sweep.countedGroup, "rings");
  EXPECT_EQ(c.sweep.objectCounts, (std::vector<int>{10, 20, 30}));
  EXPECT_EQ(c.sweep.repeats, 2);
  EXPECT_EQ(c.sweep.strategies, (std::vector<std::string>{"ours", "cullide"}));
  EXPECT_EQ(c.culling.visibility.backend, "cpu");
  EXPECT_FALSE(c.culling.visibility.conservative);
  EXPECT_EQ(c.culling.visibility.rawDepthOffset, 0.001);
  EXPECT_EQ(c.culling.visibility.threads, 3);
  EXPECT_EQ(c.culling.strategies.cis.axis, 2);
  const HierarchySpec& bvh = c.culling.strategies.cullideBvh.hierarchy;
  EXPECT_EQ(bvh.branching, 2);
  EXPECT_EQ(bvh.leafTriangles, 6);
  EXPECT_EQ(bvh.offset, 0.02);
  EXPECT_EQ(c.culling.strategies.ours.firstAxis, 1);
  const HierarchySpec& ours = c.culling.strategies.ours.hierarchy;
  EXPECT_EQ(ours.branching, 8);
  EXPECT_EQ(ours.leafTriangles, 5);
  EXPECT_EQ(ours.offset, 0.03);
}

TEST(ConfigLoader, AbsentKeysKeepTheDocumentedDefaults) {
  ScratchDir dir;
  const ScenarioConfig c = loadScenarioConfig(dir.write("min.yaml", minimal()));
  const ScenarioConfig defaults;
  EXPECT_EQ(c.seed, defaults.seed);
  EXPECT_EQ(c.dynamics.gravity, defaults.dynamics.gravity);
  EXPECT_EQ(c.dynamics.timeStep, defaults.dynamics.timeStep);
  EXPECT_EQ(c.dynamics.frames, defaults.dynamics.frames);
  EXPECT_EQ(c.sweep.resolutions, defaults.sweep.resolutions);
  EXPECT_EQ(c.sweep.strategies, defaults.sweep.strategies);
  EXPECT_EQ(c.culling.visibility.conservative, defaults.culling.visibility.conservative);
  ASSERT_EQ(c.bodies.size(), 1u);
  EXPECT_EQ(c.bodies[0].mesh.rings, 20);
  EXPECT_EQ(c.bodies[0].count, 3);
  EXPECT_TRUE(c.bodies[0].placement->randomOrientation);
}

TEST(ConfigLoader, SingleIntegerIsAOneValueList) {
  ScratchDir dir;
  const auto c =
      loadScenarioConfig(dir.write("one.yaml", minimal() + "sweep: {resolutions: 640}\n"));
  EXPECT_EQ(c.sweep.resolutions, (std::vector<int>{640}));
}

// --- one test per kind of bad input ------------------------------------------------------------

TEST_F(ConfigErrors, UnknownTopLevelKeyListsTheAllowedOnes) {
  expectError(minimal() + "sweeps: {}\n", 4, "sweeps",
              "a known key (one of environment, description, seed, dynamics, bodies, sweep, "
              "culling), got unknown key 'sweeps'");
}

TEST_F(ConfigErrors, UnknownNestedKey) {
  expectError("environment: t\ndynamics:\n  time_step: 0.01\n  timestep: 0.01\nbodies:\n" +
                  std::string(kTori),
              4, "dynamics.timestep", "one of gravity, time_step, steps_per_frame");
}

TEST_F(ConfigErrors, KeyOfAnotherMeshKindIsUnknown) {
  expectError(
      "environment: t\nbodies:\n  - name: p\n    mesh: {kind: plane, rings: 3}\n"
      "    poses: [{}]\n",
      4, "bodies[0].mesh.rings", "one of kind, plane_size, plane_cells");
}

TEST_F(ConfigErrors, DuplicateKey) {
  expectError(
      "environment: t\ndynamics:\n  frames: 10\n  frames: 20\nbodies:\n" + std::string(kTori), 4,
      "dynamics.frames", "each key once");
}

TEST_F(ConfigErrors, WrongTypeTextForNumber) {
  expectError("environment: t\ndynamics:\n  time_step: fast\nbodies:\n" + std::string(kTori), 3,
              "dynamics.time_step", "a number in (0, 1], got 'fast'");
}

TEST_F(ConfigErrors, WrongTypeListForNumber) {
  expectError("environment: t\ndynamics:\n  frames: [1, 2]\nbodies:\n" + std::string(kTori), 3,
              "dynamics.frames", "an integer in [1, 1000000], got a list of 2 items");
}

TEST_F(ConfigErrors, WrongTypeFractionForInteger) {
  expectError(minimal() + "sweep:\n  repeats: 2.5\n", 5, "sweep.repeats",
              "an integer in [1, 10000], got 2.5");
}

TEST_F(ConfigErrors, WrongTypeEmptyValue) {
  expectError("environment: t\ndynamics:\n  time_step:\nbodies:\n" + std::string(kTori), 3,
              "dynamics.time_step", "got an empty value");
}

TEST_F(ConfigErrors, WrongTypeBoolean) {
  expectError(minimal() + "culling: {visibility: {conservative: maybe}}\n", 4,
              "culling.visibility.conservative",
              "true or false, got 'maybe'");
}

TEST_F(ConfigErrors, WrongTypeVectorLength) {
  expectError("environment: t\ndynamics: {gravity: [0, -9.81]}\nbodies:\n" + std::string(kTori), 2,
              "dynamics.gravity", "a list of 3 numbers");
}

TEST_F(ConfigErrors, StrategiesMustBeAListOfStrings) {
  expectError(minimal() + "sweep:\n  strategies: ours\n", 5, "sweep.strategies",
              "a non-empty list of strategy names, got 'ours'");
  expectError(minimal() + "sweep:\n  strategies: [ours, {name: x}]\n", 5, "sweep.strategies[1]",
              "a non-empty string, got a map");
}

TEST_F(ConfigErrors, ResolutionZeroIsOutOfRange) {
  expectError(minimal() + "sweep:\n  resolutions: [500, 0]\n", 5, "sweep.resolutions[1]",
              "an integer in [1, 16384], got 0");
}

TEST_F(ConfigErrors, ResolutionTooLargeIsOutOfRange) {
  expectError(minimal() + "sweep:\n  resolutions: 100000\n", 5, "sweep.resolutions",
              "an integer in [1, 16384], got 100000");
}

TEST_F(ConfigErrors, ZeroTimeStepIsOutOfRange) {
  expectError("environment: t\ndynamics:\n  time_step: 0\nbodies:\n" + std::string(kTori), 3,
              "dynamics.time_step", "a number in (0, 1], got 0");
}

TEST_F(ConfigErrors, NonFiniteNumberIsOutOfRange) {
  expectError("environment: t\ndynamics:\n  friction: .nan\nbodies:\n" + std::string(kTori), 3,
              "dynamics.friction", "a number in [0, 1000], got '.nan'");
  expectError("environment: t\ndynamics:\n  friction: inf\nbodies:\n" + std::string(kTori), 3,
              "dynamics.friction", "a number in [0, 1000], got inf");
}

TEST_F(ConfigErrors, CountOutOfRange) {
  expectError(
      "environment: t\nbodies:\n  - name: a\n    mesh: {kind: torus}\n    count: 0\n"
      "    placement: {region_min: [0, 0, 0], region_max: [1, 1, 1]}\n",
      5, "bodies[0].count", "an integer in [1, 100000], got 0");
}

TEST_F(ConfigErrors, RestitutionOutOfRange) {
  expectError("environment: t\ndynamics: {restitution: 1.5}\nbodies:\n" + std::string(kTori), 2,
              "dynamics.restitution", "a number in [0, 1], got 1.5");
}

TEST_F(ConfigErrors, TorusTubeWiderThanItsRadius) {
  expectError(
      "environment: t\nbodies:\n  - name: a\n"
      "    mesh: {kind: torus, major_radius: 0.3, minor_radius: 0.4}\n    poses: [{}]\n",
      4, "bodies[0].mesh.minor_radius", "a minor radius below the major radius");
}

TEST_F(ConfigErrors, MissingEnvironment) {
  expectError("bodies:\n" + std::string(kTori), 1, "environment",
              "an environment name like env1 (required), got no such key");
}

TEST_F(ConfigErrors, MissingBodies) {
  expectError("environment: t\ndynamics: {frames: 3}\n", 1, "bodies",
              "a list of body groups (required), got no such key");
}

TEST_F(ConfigErrors, MissingMeshKind) {
  expectError(
      "environment: t\nbodies:\n  - name: a\n    mesh: {major_radius: 1}\n"
      "    poses: [{}]\n",
      4, "bodies[0].mesh.kind", "torus, plane or asset (required), got no such key");
}

TEST_F(ConfigErrors, UnknownMeshKind) {
  expectError("environment: t\nbodies:\n  - name: a\n    mesh: {kind: sphere}\n    poses: [{}]\n",
              4, "bodies[0].mesh.kind", "torus, plane or asset, got 'sphere'");
}

TEST_F(ConfigErrors, MissingAssetStem) {
  expectError("environment: t\nbodies:\n  - name: a\n    mesh: {kind: asset}\n    poses: [{}]\n", 4,
              "bodies[0].mesh.asset", "(required), got no such key");
}

TEST_F(ConfigErrors, NeitherPosesNorPlacement) {
  expectError("environment: t\nbodies:\n  - name: a\n    mesh: {kind: torus}\n", 3, "bodies[0]",
              "exactly one, got neither");
}

TEST_F(ConfigErrors, BothPosesAndPlacement) {
  expectError(
      "environment: t\nbodies:\n  - name: a\n    mesh: {kind: torus}\n    poses: [{}]\n"
      "    placement: {region_min: [-5, -5, -5], region_max: [5, 5, 5]}\n",
      6, "bodies[0].placement", "exactly one, got both");
}

TEST_F(ConfigErrors, WrongTypeMapForBodies) {
  expectError("environment: t\nbodies: {name: a}\n", 2, "bodies",
              "a non-empty list of body groups, got a map");
}

TEST_F(ConfigErrors, MissingFile) {
  const auto file = dir_.path() / "absent.yaml";
  try {
    (void)loadScenarioConfig(file);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              file.string() + ": expected a readable scenario file, got no such file");
  }
}

TEST_F(ConfigErrors, EmptyFile) {
  expectError("", 1, "(top level)",
              "a scenario map with environment and bodies, got an empty file");
}

TEST_F(ConfigErrors, CommentsOnlyFileIsEmpty) {
  expectError("# nothing here\n\n", 1, "(top level)", "got an empty file");
}

TEST_F(ConfigErrors, TopLevelList) {
  expectError("- a\n- b\n", 1, "(top level)", "a map with keys environment, description");
}

// The one-line message a file the YAML parser rejects gets: "<file>:<line>: expected valid YAML,
// got <the parser's words>". Returns it for further checks.
std::string expectMalformedYaml(const std::filesystem::path& file) {
  try {
    (void)loadScenarioConfig(file);
    ADD_FAILURE() << "no error for " << file;
    return {};
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(file.string() + ":", 0), 0u) << message;
    EXPECT_NE(message.find("expected valid YAML, got "), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    return message;
  }
}

TEST_F(ConfigErrors, MalformedYamlGivesTheParsersMessageAndLine) {
  const std::string message =
      expectMalformedYaml(dir_.write("bad.yaml", "environment: t\nbodies: [\n  {name: a\n"));
  EXPECT_NE(message.find("(column "), std::string::npos) << message;
}

TEST_F(ConfigErrors, TabIndentationIsMalformedYaml) {
  (void)expectMalformedYaml(dir_.write("tabs.yaml", "environment: t\nbodies:\n\t- name: a\n"));
}

TEST_F(ConfigErrors, CountDisagreesWithExplicitPoses) {
  expectError(
      "environment: t\nbodies:\n  - name: planes\n    mesh: {kind: plane}\n    count: 2\n"
      "    poses:\n      - {position: [0, 0, 0]}\n      - {}\n      - {}\n",
      6, "bodies[0].poses", "2 poses (count: 2), got 3");
}

TEST_F(ConfigErrors, RangeFromAboveTo) {
  expectError(minimal() + "sweep:\n  resolutions: {from: 1200, to: 500, step: 100}\n", 5,
              "sweep.resolutions.to", "an integer >= from (1200), got 500");
}

TEST_F(ConfigErrors, RangeStepZero) {
  expectError(minimal() + "sweep:\n  resolutions: {from: 500, to: 1200, step: 0}\n", 5,
              "sweep.resolutions.step", "an integer in [1, 16384], got 0");
}

TEST_F(ConfigErrors, RangeWithoutStep) {
  expectError(minimal() + "sweep:\n  resolutions: {from: 500, to: 1200}\n", 5,
              "sweep.resolutions.step", "(required), got no such key");
}

TEST_F(ConfigErrors, RangeWithUnknownKey) {
  expectError(minimal() + "sweep:\n  resolutions: {from: 500, until: 1200, step: 1}\n", 5,
              "sweep.resolutions.until", "one of from, to, step");
}

TEST_F(ConfigErrors, RepeatedValueInList) {
  expectError(minimal() + "sweep:\n  resolutions: [500, 600, 500]\n", 5, "sweep.resolutions",
              "distinct values, got 500 twice");
}

TEST_F(ConfigErrors, EmptyList) {
  expectError(minimal() + "sweep:\n  resolutions: []\n", 5, "sweep.resolutions",
              "a list of integers, one integer, or a range");
}

TEST_F(ConfigErrors, DuplicateGroupName) {
  expectError("environment: t\nbodies:\n" + std::string(kTori) + std::string(kTori), 4,
              "bodies[1].name", "a group name used once");
}

TEST_F(ConfigErrors, CountedGroupMustExist) {
  expectError(minimal() + "sweep:\n  counted_group: rings\n  object_counts: [5]\n", 5,
              "sweep.counted_group", "the name of a body group (tori), got 'rings'");
}

TEST_F(ConfigErrors, CountedGroupNeedsObjectCounts) {
  expectError(minimal() + "sweep:\n  counted_group: tori\n", 5, "sweep.counted_group",
              "object_counts beside counted_group");
}

TEST_F(ConfigErrors, CountedGroupMustBePlacedRandomly) {
  expectError(
      "environment: t\nbodies:\n  - {name: p, mesh: {kind: plane}, poses: [{}]}\n"
      "sweep: {counted_group: p, object_counts: [1, 2]}\n",
      4, "sweep.counted_group", "a group with random placement");
}

TEST_F(ConfigErrors, RegionMaxBelowRegionMin) {
  expectError(
      "environment: t\nbodies:\n  - name: a\n    mesh: {kind: torus}\n    placement:\n"
      "      region_min: [0, 0, 0]\n      region_max: [1, -1, 1]\n",
      7, "bodies[0].placement.region_max", "each coordinate >= region_min's");
}

TEST_F(ConfigErrors, SpeedMaxBelowSpeedMin) {
  expectError(
      "environment: t\nbodies:\n  - name: a\n    mesh: {kind: torus}\n    placement:\n"
      "      region_min: [0, 0, 0]\n      region_max: [9, 9, 9]\n      speed_min: 2\n"
      "      speed_max: 1\n",
      9, "bodies[0].placement.speed_max", "speed_max >= speed_min");
}

TEST_F(ConfigErrors, RegionOutsideTheContainer) {
  expectError(
      "environment: t\ndynamics: {container_half_extent: 5}\nbodies:\n  - name: a\n"
      "    mesh: {kind: torus}\n    placement:\n      region_min: [-5, -4, -4]\n"
      "      region_max: [4, 4, 4]\n",
      7, "bodies[0].placement.region_min", "fit inside the container (half extent 5)");
}

TEST_F(ConfigErrors, TooManyBodiesForTheRegion) {
  expectError(
      "environment: t\nbodies:\n  - name: a\n    mesh: {kind: torus}\n    count: 100\n"
      "    placement: {region_min: [0, 0, 0], region_max: [1, 1, 1]}\n",
      6, "bodies[0].placement", "a region where 100 bodies");
  // The sweep's largest count is what has to fit.
  expectError(minimal() + "sweep: {counted_group: tori, object_counts: [3, 5000]}\n", 3,
              "bodies[0].placement", "a region where 5000 bodies");
}

// --- integer lists of the command line -----------------------------------------------------------

TEST(ParseIntList, AcceptsListsRangesAndMixes) {
  EXPECT_EQ(parseIntList("500,600"), (std::vector<int>{500, 600}));
  EXPECT_EQ(parseIntList("800"), (std::vector<int>{800}));
  EXPECT_EQ(parseIntList("500:1200:100"),
            (std::vector<int>{500, 600, 700, 800, 900, 1000, 1100, 1200}));
  EXPECT_EQ(parseIntList("50:200:25").size(), 7u);
  EXPECT_EQ(parseIntList(" 500 , 600:800:100 ,+7"), (std::vector<int>{500, 600, 700, 800, 7}));
  EXPECT_EQ(parseIntList("1:10:4"), (std::vector<int>{1, 5, 9}));  // stops before passing `to`
}

TEST(ParseIntList, RejectsMalformedText) {
  const auto messageOf = [](std::string_view text) -> std::string {
    try {
      (void)parseIntList(text);
    } catch (const InputError& e) {
      return e.what();
    }
    return "<no error>";
  };
  EXPECT_EQ(messageOf("500,abc"), "'500,abc': expected an integer, got 'abc'");
  EXPECT_NE(messageOf("").find("expected integers like 500,600"), std::string::npos);
  EXPECT_NE(messageOf("500,").find("got an empty item"), std::string::npos);
  EXPECT_NE(messageOf("500:1200").find("expected a range from:to:step, got '500:1200'"),
            std::string::npos);
  EXPECT_NE(messageOf("500:1200:0").find("expected a range step >= 1, got 0"), std::string::npos);
  EXPECT_NE(messageOf("1200:500:100").find("expected a range with from <= to, got 1200 > 500"),
            std::string::npos);
  EXPECT_NE(messageOf("1:2000000000:1").find("at most 100000 values"), std::string::npos);
  EXPECT_NE(messageOf("99999999999").find("expected an integer"), std::string::npos);
  EXPECT_NE(messageOf("1.5").find("expected an integer, got '1.5'"), std::string::npos);
}

// --- scenes from configs -------------------------------------------------------------------------

TEST(SceneBuilder, OneSharedMeshPerGroupAndObjectsInGroupOrder) {
  ScratchDir dir;
  const auto config = loadScenarioConfig(dir.write("s.yaml", R"(environment: t
bodies:
  - {name: floor, mesh: {kind: plane, plane_cells: 4}, fixed: true, poses: [{}, {}]}
  - {name: tori, mesh: {kind: torus, rings: 10, sides: 8}, count: 3,
     placement: {region_min: [-5, -5, -5], region_max: [5, 5, 5]}}
sweep: {counted_group: tori, object_counts: [1, 7]}
)"));
  const SceneGeometry scene = buildScene(config, {});
  ASSERT_EQ(scene.meshes.size(), 2u);
  EXPECT_EQ(scene.meshes[0].triangleCount(), 32u);
  EXPECT_EQ(scene.meshes[1].triangleCount(), 160u);
  EXPECT_EQ(scene.meshes[0].name, "floor");
  ASSERT_EQ(scene.objectCount(), 5u);
  for (ObjectId i = 0; i < 5; ++i) {
    EXPECT_EQ(scene.objects[i].mesh, i < 2 ? 0u : 1u);
    EXPECT_EQ(scene.objects[i].fixed, i < 2);
    EXPECT_EQ(scene.objects[i].group, i < 2 ? "floor" : "tori");
  }
  EXPECT_EQ(&scene.meshOf(3), &scene.meshOf(4));

  const ScenarioConfig seven = withObjectCount(config, 7);
  EXPECT_EQ(seven.bodies[1].count, 7);
  EXPECT_EQ(config.bodies[1].count, 3);  // the original is untouched
  EXPECT_EQ(buildScene(seven, {}).objectCount(), 9u);
  EXPECT_THROW((void)withObjectCount(config, 0), InputError);
}

TEST(SceneBuilder, WithObjectCountNeedsACountedGroup) {
  ScratchDir dir;
  const auto config = loadScenarioConfig(dir.write("s.yaml", minimal()));
  EXPECT_THROW((void)withObjectCount(config, 5), InputError);
}

TEST(SceneBuilder, MissingAssetIsAnInputError) {
  ScratchDir dir;
  const auto config = loadScenarioConfig(
      dir.write("s.yaml",
                "environment: t\nbodies:\n  - {name: d, mesh: {kind: asset, asset: nothing_here}, "
                "poses: [{}]}\n"));
  try {
    (void)buildScene(config, {dir.path().string()});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("scripts/fetch-assets.sh"), std::string::npos) << e.what();
  }
}

TEST(SceneBuilder, AssetIsNormalisedToItsSize) {
  ScratchDir dir;
  dir.write("assets/wedge.obj",
            "v 10 10 10\nv 14 10 10\nv 10 12 10\nv 10 10 11\n"
            "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  const auto config = loadScenarioConfig(
      dir.write("s.yaml",
                "environment: t\nbodies:\n  - {name: w, mesh: {kind: asset, asset: wedge, "
                "asset_size: 2}, poses: [{}]}\n"));
  const SceneGeometry scene = buildScene(config, {(dir.path() / "assets").string()});
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.meshes[0].triangleCount(), 4u);
  EXPECT_NEAR(scene.meshes[0].bounds().sizes().maxCoeff(), 2.0, 1e-6);
  EXPECT_NEAR(scene.meshes[0].bounds().center().norm(), 0.0, 1e-6);
}

// A built scene names the file each asset mesh was loaded from, and assetFiles records that file
// (each asset and file once), not the copy the asset path finds after the build.
TEST(SceneBuilder, AssetMeshesNameTheFileTheyWereLoadedFrom) {
  ScratchDir dir;
  const std::string wedge =
      "v 10 10 10\nv 14 10 10\nv 10 12 10\nv 10 10 11\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  dir.write("first/notes.txt", "");
  const auto loaded = dir.write("second/wedge.obj", wedge);
  const auto config = loadScenarioConfig(
      dir.write("s.yaml",
                "environment: t\nbodies:\n"
                "  - {name: w, mesh: {kind: asset, asset: wedge}, poses: [{}]}\n"
                "  - {name: v, mesh: {kind: asset, asset: wedge}, poses: [{}]}\n"));
  const std::vector<std::string> dirs{(dir.path() / "first").string(),
                                      (dir.path() / "second").string()};
  const SceneGeometry scene = buildScene(config, dirs);
  ASSERT_EQ(scene.meshes.size(), 2u);
  EXPECT_EQ(scene.meshes[0].source, loaded.string());

  const auto later = dir.write("first/wedge.obj", wedge + "# another copy\n");
  const std::vector<AssetFile> files = assetFiles(config, scene);
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files[0].asset, "wedge");
  EXPECT_EQ(files[0].path, loaded);
  EXPECT_EQ(files[0].bytes, wedge.size());
  EXPECT_EQ(files[0].sha256, fileSha256(loaded));
  EXPECT_NE(files[0].sha256, fileSha256(later));
  EXPECT_EQ(assetFiles(config, dirs).at(0).path, later);  // what the path finds now
  EXPECT_TRUE(assetFiles(config, scene, files).empty());  // known: not again
  const std::vector<AssetFile> rebuilt = assetFiles(config, buildScene(config, dirs), files);
  ASSERT_EQ(rebuilt.size(), 1u);
  EXPECT_EQ(rebuilt[0].path, later);
}

// --- the shipped environments --------------------------------------------------------------------

std::filesystem::path shipped(const char* name) {
  return std::filesystem::path(CDBENCH_SOURCE_DIR) / "configs" / name;
}

const std::vector<int> kThesisResolutions{500, 600, 700, 800, 900, 1000, 1100, 1200};

TEST(ShippedConfigs, Env1Is50ToriOverTwoPlanes) {
  const ScenarioConfig c = loadScenarioConfig(shipped("env1.yaml"));
  EXPECT_EQ(c.environment, "env1");
  EXPECT_EQ(c.sweep.resolutions, kThesisResolutions);
  EXPECT_EQ(c.sweep.repeats, 10);
  EXPECT_TRUE(c.sweep.countedGroup.empty());
  const SceneGeometry scene = buildScene(c, {});
  ASSERT_EQ(scene.objectCount(), 52u);
  int planes = 0, tori = 0;
  for (ObjectId i = 0; i < scene.objectCount(); ++i) {
    const auto triangles = scene.meshOf(i).triangleCount();
    if (scene.objects[i].fixed) {
      EXPECT_EQ(triangles, 1800u);
      ++planes;
    } else {
      EXPECT_EQ(triangles, 800u);
      ++tori;
    }
  }
  EXPECT_EQ(planes, 2);
  EXPECT_EQ(tori, 50);
  EXPECT_LT(c.dynamics.gravity[1], 0);
}

TEST(ShippedConfigs, Env2Is12DragonsOverTwoPlanes) {
  const ScenarioConfig c = loadScenarioConfig(shipped("env2.yaml"));
  EXPECT_EQ(c.environment, "env2");
  EXPECT_EQ(c.sweep.resolutions, kThesisResolutions);
  EXPECT_EQ(c.sweep.repeats, 10);
  if (!test::findTestAsset("dragon_vrip_res3")) {
    GTEST_SKIP() << "dragon_vrip_res3 not on the asset path (scripts/fetch-assets.sh)";
  }
  const SceneGeometry scene = buildScene(c, test::testAssetDirs());
  ASSERT_EQ(scene.objectCount(), 14u);
  int dragons = 0;
  for (ObjectId i = 0; i < scene.objectCount(); ++i) {
    if (scene.objects[i].fixed) {
      EXPECT_EQ(scene.meshOf(i).triangleCount(), 1800u);
    } else {
      EXPECT_EQ(scene.meshOf(i).triangleCount(), 47794u);
      EXPECT_NEAR(scene.meshOf(i).bounds().sizes().maxCoeff(), 1.5, 1e-5);
      ++dragons;
    }
  }
  EXPECT_EQ(dragons, 12);
}

TEST(ShippedConfigs, Env3SweepsToriInAClosedCube) {
  const ScenarioConfig c = loadScenarioConfig(shipped("env3.yaml"));
  EXPECT_EQ(c.environment, "env3");
  EXPECT_EQ(c.sweep.resolutions, (std::vector<int>{800}));
  EXPECT_EQ(c.sweep.objectCounts, (std::vector<int>{50, 75, 100, 125, 150, 175, 200}));
  EXPECT_EQ(c.dynamics.gravity, (Vec3{0, 0, 0}));
  EXPECT_GT(c.dynamics.containerHalfExtent, 0);
  for (int n : c.sweep.objectCounts) {
    const SceneGeometry scene = buildScene(withObjectCount(c, n), {});
    ASSERT_EQ(scene.objectCount(), std::size_t(n));
    EXPECT_EQ(scene.meshOf(0).triangleCount(), 800u);
  }
}

}  // namespace
}  // namespace cdb
