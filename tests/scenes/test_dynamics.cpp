// Rigid-body dynamics: determinism, contact (resting, stacking, the closed cube), fixed bodies,
// poses through the centre-of-mass offset, mass fall-back, and instability reporting.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/Errors.h"
#include "scenes/BodyPlacement.h"
#include "scenes/ConfigLoader.h"
#include "scenes/ContactReduction.h"
#include "scenes/MeshMeasures.h"
#include "scenes/PoseRecording.h"
#include "scenes/RigidBodySimulation.h"
#include "scenes/SceneBuilder.h"
#include "tests/scenes/DynamicsTestScenes.h"

namespace cdb {
namespace {

using namespace dynamics_test;

constexpr double kTubeRadius = 0.2;  // MeshSpec's default torus: R 0.5, r 0.2

std::vector<Pose> run(RigidBodySimulation& simulation, int frames) {
  std::vector<Pose> all;
  for (int f = 0; f < frames; ++f) {
    simulation.stepFrame();
    all.insert(all.end(), simulation.poses().begin(), simulation.poses().end());
  }
  return all;
}

std::uint64_t hashOf(std::vector<Pose> poses) {
  PoseRecording recording;
  recording.poses = std::move(poses);
  return recording.hash();
}

double lowestY(const SceneGeometry& scene, ObjectId id, const Pose& pose) {
  double y = INFINITY;
  for (const auto& v : scene.meshOf(id).vertices) y = std::min(y, pose.apply(v.cast<double>()).y());
  return y;
}

template <class Error>
std::string errorOf(const std::function<void()>& action) {
  try {
    action();
  } catch (const Error& error) {
    return error.what();
  }
  return "(no error)";
}

bool samePose(const Pose& a, const Pose& b) {
  return a.translation == b.translation && a.rotation.coeffs() == b.rotation.coeffs();
}

TEST(RigidBodyDynamics, SameSeedGivesBitIdenticalFramesEvenWhenInterleaved) {
  // The cube (trimesh against trimesh and walls) and a drop onto the floor (trimesh floor).
  for (const ScenarioConfig& config :
       {cubeScenario(30, 3.0), dropScenario({at(0, 0.8, 0, {20, 0, 10}), at(0.1, 1.6, 0.05)})}) {
    SCOPED_TRACE(config.environment);
    const SceneGeometry scene = sceneFor(config);
    RigidBodySimulation alone(config, scene, 11);
    const std::uint64_t reference = hashOf(run(alone, 60));

    // Two worlds stepped in turn share ODE's globals (the solver's random seed, collider
    // caches): they must not notice each other.
    RigidBodySimulation a(config, scene, 11), b(config, scene, 11);
    std::vector<Pose> posesA, posesB;
    for (int f = 0; f < 60; ++f) {
      a.stepFrame();
      b.stepFrame();
      posesA.insert(posesA.end(), a.poses().begin(), a.poses().end());
      posesB.insert(posesB.end(), b.poses().begin(), b.poses().end());
    }
    EXPECT_EQ(hashOf(posesA), reference);
    EXPECT_EQ(hashOf(posesB), reference);
  }
}

TEST(RigidBodyDynamics, DifferentSeedGivesDifferentFrames) {
  const ScenarioConfig config = cubeScenario(10);
  const SceneGeometry scene = sceneFor(config);
  RigidBodySimulation one(config, scene, 1), two(config, scene, 2);
  EXPECT_NE(hashOf(run(one, 10)), hashOf(run(two, 10)));
}

TEST(RigidBodyDynamics, CountsFramesAndStartsAtTheInitialPoses) {
  const ScenarioConfig config = dropScenario({at(0.3, 1.0, -0.2, {10, 20, 30})});
  const SceneGeometry scene = sceneFor(config);
  RigidBodySimulation simulation(config, scene, 1);
  EXPECT_EQ(simulation.frame(), 0);
  ASSERT_EQ(simulation.poses().size(), 2u);
  EXPECT_TRUE(samePose(simulation.poses()[1], poseFrom(config.bodies[1].poses[0])));
  simulation.stepFrame();
  simulation.stepFrame();
  EXPECT_EQ(simulation.frame(), 2);
}

TEST(RigidBodyDynamics, RotationDegreesAreIntrinsicXThenYThenZ) {
  // Intrinsic X then Z: local x turns to y about z, and that y to world z about x.
  const Pose xz = poseFrom(at(0, 0, 0, {90, 0, 90}));
  EXPECT_TRUE((xz.rotation * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
  const Pose xy = poseFrom(at(1, 2, 3, {90, 90, 0}));
  EXPECT_TRUE((xy.rotation * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-12));
  EXPECT_EQ(xy.translation, Eigen::Vector3d(1, 2, 3));
}

TEST(RigidBodyDynamics, FixedBodiesNeverMove) {
  ScenarioConfig config = dropScenario({at(0, 0.8, 0, {30, 0, 0}), at(0.2, 1.6, 0)});
  config.bodies[0].poses[0] = at(0.5, -0.1, 0.25, {5, 10, 0});  // a slightly tilted floor
  const SceneGeometry scene = sceneFor(config);
  RigidBodySimulation simulation(config, scene, 1);
  const Pose floor = simulation.poses()[0];
  EXPECT_TRUE(samePose(floor, poseFrom(config.bodies[0].poses[0])));
  for (int f = 0; f < 100; ++f) {
    simulation.stepFrame();
    ASSERT_TRUE(samePose(simulation.poses()[0], floor)) << "frame " << simulation.frame();
  }
  // The tori did move: the test is not vacuous.
  EXPECT_LT(simulation.poses()[1].translation.y(), 0.5);
}

TEST(RigidBodyDynamics, DroppedTorusComesToRestOnThePlane) {
  const ScenarioConfig config = dropScenario({at(0.1, 1.0, -0.1, {25, 0, 10})});
  const SceneGeometry scene = sceneFor(config);
  RigidBodySimulation simulation(config, scene, 1);
  double deepest = 0;
  for (int f = 0; f < 150; ++f) {
    simulation.stepFrame();
    deepest = std::max(deepest, -lowestY(scene, 1, simulation.poses()[1]));
  }
  EXPECT_LT(deepest, 0.05) << "the torus sank into the plane";
  const Pose settled = simulation.poses()[1];
  EXPECT_NEAR(settled.translation.y(), kTubeRadius, 0.02) << "a torus at rest lies flat";
  for (int f = 0; f < 20; ++f) simulation.stepFrame();
  EXPECT_LT((simulation.poses()[1].translation - settled.translation).norm(), 2e-3) << "still moving";
}

TEST(RigidBodyDynamics, DroppedToriStackOnEachOther) {
  const ScenarioConfig config = dropScenario(
      {at(0, 0.8, 0, {20, 0, 10}), at(0.1, 1.6, 0.05), at(-0.05, 2.4, 0.1, {0, 0, 5}), at(0.1, 3.2, 0)});
  const SceneGeometry scene = sceneFor(config);
  RigidBodySimulation simulation(config, scene, 1);
  double deepest = 0;
  for (int f = 0; f < 250; ++f) {
    simulation.stepFrame();
    for (ObjectId id = 1; id < scene.objectCount(); ++id) {
      deepest = std::max(deepest, -lowestY(scene, id, simulation.poses()[id]));
    }
  }
  EXPECT_LT(deepest, 0.05) << "a torus sank into the plane";
  // Resting on another torus, not on the floor: its lowest point is a tube diameter up.
  double highestBottom = 0;
  for (ObjectId id = 1; id < scene.objectCount(); ++id) {
    highestBottom = std::max(highestBottom, lowestY(scene, id, simulation.poses()[id]));
  }
  EXPECT_GT(highestBottom, 2 * kTubeRadius - 0.05);
}

TEST(RigidBodyDynamics, ClosedCubeKeepsBodiesInsideWithoutGravity) {
  const double halfExtent = 4.0;
  const ScenarioConfig config = cubeScenario(60, halfExtent);
  const SceneGeometry scene = sceneFor(config);
  RigidBodySimulation simulation(config, scene, 3);
  const std::vector<Pose> start(simulation.poses().begin(), simulation.poses().end());
  double farthest = 0;
  for (int f = 0; f < 200; ++f) {
    simulation.stepFrame();
    for (const Pose& pose : simulation.poses()) {
      farthest = std::max(farthest, pose.translation.cwiseAbs().maxCoeff());
    }
  }
  // The tube must stay inside: centres at most a tube radius from a wall, plus a little contact
  // penetration.
  EXPECT_LT(farthest, halfExtent - kTubeRadius + 0.05);
  // At 1..3 units/s for 4 s in an 8-unit cube every body has travelled.
  std::size_t moved = 0;
  for (ObjectId id = 0; id < scene.objectCount(); ++id) {
    moved += (simulation.poses()[id].translation - start[id].translation).norm() > 0.1;
  }
  EXPECT_EQ(moved, scene.objectCount());
}

TEST(RigidBodyDynamics, ShippedEnv3PlacesAndKeepsItsToriInsideTheCube) {
  const ScenarioConfig config =
      loadScenarioConfig(std::filesystem::path(CDBENCH_SOURCE_DIR) / "configs" / "env3.yaml");
  const SceneGeometry scene = sceneFor(config);
  const double halfExtent = config.dynamics.containerHalfExtent;
  ASSERT_GT(halfExtent, 0);
  RigidBodySimulation simulation(config, scene, config.seed);
  double farthest = 0;
  for (int f = 0; f < 40; ++f) {
    simulation.stepFrame();
    for (const Pose& pose : simulation.poses()) {
      farthest = std::max(farthest, pose.translation.cwiseAbs().maxCoeff());
    }
  }
  EXPECT_LT(farthest, halfExtent);
}

// The sweep's every simulation must start: each repeat r is seeded seed + r, and env3's largest
// count fills its cube near the placement limit.
TEST(RigidBodyDynamics, ShippedEnv3PlacesItsLargestCountForEveryRepeat) {
  const ScenarioConfig config =
      loadScenarioConfig(std::filesystem::path(CDBENCH_SOURCE_DIR) / "configs" / "env3.yaml");
  const int largest = *std::max_element(config.sweep.objectCounts.begin(), config.sweep.objectCounts.end());
  const ScenarioConfig full = withObjectCount(config, largest);
  const SceneGeometry scene = sceneFor(full);
  for (int r = 0; r < config.sweep.repeats; ++r)
    EXPECT_NO_THROW(RigidBodySimulation(full, scene, config.seed + static_cast<std::uint64_t>(r)))
        << "repeat " << r;
}

TEST(RigidBodyDynamics, PoseMapsMeshCoordinatesThroughTheCentreOfMassOffset) {
  // A torus whose mesh is off its local origin: ODE's body sits at the centre of mass, the pose
  // must still place the mesh. Without gravity and velocity nothing may move.
  ScenarioConfig config;
  config.dynamics.gravity = {0, 0, 0};
  BodyGroup group = torusGroup("offset", 1);
  group.poses = {at(1, 2, 3, {30, 40, 50})};
  config.bodies = {group};
  SceneGeometry scene = sceneFor(config);
  for (auto& v : scene.meshes[0].vertices) v += Eigen::Vector3f(1.0f, 0.5f, -0.25f);
  RigidBodySimulation still(config, scene, 1);
  const Pose start = still.poses()[0];
  for (int f = 0; f < 5; ++f) still.stepFrame();
  EXPECT_TRUE(still.poses()[0].translation.isApprox(start.translation, 1e-12));
  EXPECT_TRUE(still.poses()[0].rotation.isApprox(start.rotation, 1e-12));

  // Spinning freely, it turns about its centre of mass (the torus centre), which stays put.
  group.poses.clear();
  RandomPlacement spin;
  spin.angularSpeedMax = 5.0;
  group.placement = spin;
  config.bodies = {group};
  RigidBodySimulation spinning(config, scene, 1);
  const Eigen::Vector3d centreLocal(1.0, 0.5, -0.25);
  const Eigen::Vector3d centre = spinning.poses()[0].apply(centreLocal);
  const Eigen::Quaterniond initial = spinning.poses()[0].rotation;
  for (int f = 0; f < 20; ++f) spinning.stepFrame();
  EXPECT_LT((spinning.poses()[0].apply(centreLocal) - centre).norm(), 1e-5);
  EXPECT_GT(spinning.poses()[0].rotation.angularDistance(initial), 0.01) << "it should have turned";
}

TEST(RigidBodyDynamics, OpenMeshFallsBackToProxyMassAndFallsFreely) {
  ScenarioConfig config;
  BodyGroup group = torusGroup("open", 1);
  group.poses = {at(0, 5, 0)};
  config.bodies = {group};
  SceneGeometry scene = sceneFor(config);
  scene.meshes[0].triangles.resize(scene.meshes[0].triangles.size() - 2);  // a hole
  ASSERT_FALSE(isClosedMesh(scene.meshes[0]));
  RigidBodySimulation simulation(config, scene, 1);
  const int frames = 10;
  for (int f = 0; f < frames; ++f) simulation.stepFrame();
  // ODE integrates v += g h, then x += v h: after n steps the drop is g h^2 n (n + 1) / 2.
  const int n = frames * config.dynamics.stepsPerFrame;
  const double h = config.dynamics.timeStep;
  const double drop = 9.81 * h * h * n * (n + 1) / 2;
  EXPECT_NEAR(simulation.poses()[0].translation.y(), 5.0 - drop, 1e-9);
  EXPECT_TRUE(simulation.poses()[0].rotation.isApprox(Eigen::Quaterniond::Identity(), 1e-12));
}

TEST(RigidBodyDynamics, FlatMovingBodyIsAnInputError) {
  ScenarioConfig config = dropScenario({});
  config.bodies[0].fixed = false;
  SceneGeometry scene = sceneFor(config);
  const std::string message =
      errorOf<InputError>([&] { RigidBodySimulation simulation(config, scene, 1); });
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "group floor", message);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "encloses no volume", message);
}

TEST(RigidBodyDynamics, ObjectOfUnknownGroupIsAnInputError) {
  const ScenarioConfig config = dropScenario({at(0, 1, 0)});
  SceneGeometry scene = sceneFor(config);
  scene.objects[1].group = "ghost";
  const std::string message =
      errorOf<InputError>([&] { RigidBodySimulation simulation(config, scene, 1); });
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "object 1 names group 'ghost'", message);
}

TEST(RigidBodyDynamics, BodyWithoutPoseOrPlacementIsAnInputError) {
  ScenarioConfig config = dropScenario({at(0, 1, 0)});
  config.bodies[1].count = 2;
  const SceneGeometry scene = sceneFor(config);
  const std::string message =
      errorOf<InputError>([&] { RigidBodySimulation simulation(config, scene, 1); });
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "group torus: body 1 has no pose", message);
}

TEST(RigidBodyDynamics, DynamicsThatOdeCannotRunAreInputErrors) {
  ScenarioConfig config = dropScenario({at(0, 1, 0)});
  config.sourcePath = "env.yaml";
  config.dynamics.timeStep = 0;
  const SceneGeometry scene = sceneFor(config);
  EXPECT_EQ(errorOf<InputError>([&] { RigidBodySimulation simulation(config, scene, 1); }),
            "env.yaml: dynamics.time_step: expected a number > 0");
  config.dynamics.timeStep = 0.01;
  config.dynamics.maxContactsPerPair = 0;
  EXPECT_EQ(errorOf<InputError>([&] { RigidBodySimulation simulation(config, scene, 1); }),
            "env.yaml: dynamics.max_contacts_per_pair: expected an integer in 1..65535");
}

TEST(RigidBodyDynamics, NonFiniteStateThrowsRunErrorNamingFrameAndBody) {
  ScenarioConfig config = dropScenario({at(0, 1, 0)});
  config.dynamics.gravity = {0, -1e308, 0};  // one step overflows the velocity to infinity
  config.dynamics.timeStep = 10;
  const SceneGeometry scene = sceneFor(config);
  RigidBodySimulation simulation(config, scene, 1);
  const std::string message = errorOf<RunError>([&] { simulation.stepFrame(); });
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "frame 1: body 1 (group torus) became unstable (non-finite", message);
  // The world is unusable now; stepping again repeats the error instead of producing frames.
  EXPECT_EQ(errorOf<RunError>([&] { simulation.stepFrame(); }), message);
  EXPECT_EQ(simulation.frame(), 0);
}

TEST(RigidBodyDynamics, RunawaySpeedThrowsRunErrorNamingFrameAndBody) {
  ScenarioConfig config = cubeScenario(3, 0.0);
  config.bodies[0].placement->speedMin = 2e4;
  config.bodies[0].placement->speedMax = 2e4;
  config.bodies[0].placement->regionMin = {-5, -5, -5};
  config.bodies[0].placement->regionMax = {5, 5, 5};
  const SceneGeometry scene = sceneFor(config);
  RigidBodySimulation simulation(config, scene, 1);
  const std::string message =
      errorOf<RunError>([&] { simulation.stepFrame(); });
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "frame 1: body 0 (group torus) became unstable (speed", message);
}

TEST(RigidBodyDynamics, PlacementThatCannotFitThrowsRunError) {
  ScenarioConfig config = cubeScenario(200, 0.0);
  config.bodies[0].placement->regionMin = {-1, -1, -1};
  config.bodies[0].placement->regionMax = {1, 1, 1};
  const SceneGeometry scene = sceneFor(config);
  const std::string message =
      errorOf<RunError>([&] { RigidBodySimulation simulation(config, scene, 1); });
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "cannot place 200 bodies of group torus in region (-1, -1, -1)..(1, 1, 1)", message);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "enlarge region", message);
}

TEST(DynamicsMeshMeasures, TorusIsClosedWithItsVolumeAndSphere) {
  const Mesh torus = makeTorus(0.5, 0.2, 20, 20);
  EXPECT_TRUE(isClosedMesh(torus));
  const double exact = 2 * M_PI * M_PI * 0.5 * 0.2 * 0.2;
  EXPECT_NEAR(signedVolume(torus), exact, 0.05 * exact);  // a 20 x 20 polygon is a bit smaller
  const BoundingSphere sphere = boundingSphere(torus);
  EXPECT_LT(sphere.centre.norm(), 1e-6);
  EXPECT_NEAR(sphere.radius, 0.7, 1e-6);
}

TEST(DynamicsMeshMeasures, OpenFlippedAndSeamDuplicatedMeshes) {
  Mesh torus = makeTorus(0.5, 0.2, 20, 20);
  Mesh inverted = torus;
  for (auto& t : inverted.triangles) std::swap(t[1], t[2]);
  EXPECT_TRUE(isClosedMesh(inverted));
  EXPECT_LT(signedVolume(inverted), 0);

  // Every triangle with its own copies of its vertices: closed once positions are welded.
  Mesh soup;
  for (const auto& t : torus.triangles) {
    const auto base = std::uint32_t(soup.vertices.size());
    for (std::uint32_t v : t) soup.vertices.push_back(torus.vertices[v]);
    soup.triangles.push_back({base, base + 1, base + 2});
  }
  EXPECT_TRUE(isClosedMesh(soup));

  torus.triangles.pop_back();
  EXPECT_FALSE(isClosedMesh(torus));
  EXPECT_FALSE(isClosedMesh(makePlane(10.0, 30)));
}

TEST(DynamicsContactPicker, KeepsTheDeepestAndSpreadsTheRest) {
  std::vector<dContact> contacts(6);
  const double xs[6] = {0.0, 0.01, 0.02, 1.0, 1.01, 0.5};
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    contacts[i] = dContact{};
    contacts[i].geom.pos[0] = xs[i];
    contacts[i].geom.depth = 0.01;
  }
  contacts[1].geom.depth = 0.05;
  ContactPicker picker;
  const auto two = picker.pick(contacts, 6, 2);
  EXPECT_EQ(std::vector<std::size_t>(two.begin(), two.end()), (std::vector<std::size_t>{1, 4}));
  const auto three = picker.pick(contacts, 6, 3);
  EXPECT_EQ(std::vector<std::size_t>(three.begin(), three.end()), (std::vector<std::size_t>{1, 4, 5}));
  EXPECT_EQ(picker.pick(contacts, 4, 8).size(), 4u);
}

}  // namespace
}  // namespace cdb
