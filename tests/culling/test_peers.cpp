// The CPU peers (FCL, Bullet, ODE) on their own: hand-built torus pairs whose answer is known, a
// torus a micrometre above and below a plane, and a random scene of 40 tori against the ground
// truth. Each peer must agree with the ground truth exactly: none needs a tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "RandomScenes.h"
#include "core/Errors.h"
#include "culling/DetectorRegistry.h"
#include "culling/exact/ExactPhase.h"
#include "culling/exact/GroundTruth.h"
#include "culling/visibility/ScriptedVisibilityOracle.h"
#include "scenes/ProceduralMeshes.h"

namespace cdb {
namespace {

// Pairs a peer decides on each frame of `scene`.
std::vector<std::vector<ObjectPair>> peerPairs(const std::string& peer,
                                               const testing::RandomScene& scene) {
  auto detector = DetectorRegistry::builtin().createPeer(peer, {});
  detector->attach(scene.scene);
  std::vector<std::vector<ObjectPair>> out;
  for (std::size_t f = 0; f < scene.frames.size(); ++f) {
    const DetectedFrame d = detector->detect({scene.frames[f], int(f)});
    EXPECT_FALSE(d.culled.has_value()) << peer;
    EXPECT_EQ(d.exactMs, 0.0) << peer;
    out.push_back(d.report.collidingPairs);
  }
  return out;
}

// Two tori of major radius 0.5 and minor radius 0.2 (axis y), the first at the identity.
testing::RandomScene torusPair(const Pose& second) {
  testing::RandomScene s;
  s.scene.meshes.push_back(makeTorus(0.5, 0.2, 20, 20));
  s.scene.objects = {{0, false, "torus"}, {0, false, "torus"}};
  s.frames.push_back({Pose{}, second});
  return s;
}

// The second torus turned a quarter about x (axis z) and moved by `dx` along x.
Pose quarterTurned(double dx) {
  Pose p;
  p.rotation = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX());
  p.translation = {dx, 0, 0};
  return p;
}

// A torus lying on a plane (30 x 30 cells, normal +y), both tilted by 0.3 about z, its lowest
// vertices `gap` above the plane (negative: below it).
testing::RandomScene torusOnPlane(double gap) {
  testing::RandomScene s;
  s.scene.meshes.push_back(makeTorus(0.5, 0.2, 20, 20));
  s.scene.meshes.push_back(makePlane(3.0, 30));
  s.scene.objects = {{0, false, "torus"}, {1, true, "plane"}};
  const Eigen::Quaterniond tilt(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()));
  Pose torus;
  torus.rotation = tilt;
  torus.translation =
      tilt * Eigen::Vector3d(0.05, -s.scene.meshes[0].bounds().min().y() + gap, 0.03);
  Pose plane;
  plane.rotation = tilt;
  s.frames.push_back({torus, plane});
  return s;
}

class PeerTest : public ::testing::TestWithParam<std::string> {};

TEST_P(PeerTest, InterpenetratingToriCollide) {
  Pose side;  // same plane, centres 0.6 apart: the tubes cross deeply
  side.translation = {0.6, 0, 0};
  const std::vector<ObjectPair> both = {{0, 1}};
  EXPECT_EQ(peerPairs(GetParam(), torusPair(side))[0], both);
  // Linked like chain links but 0.2 off centre: the tubes cross, 0.1 deep.
  EXPECT_EQ(peerPairs(GetParam(), torusPair(quarterTurned(0.3)))[0], both);
}

TEST_P(PeerTest, ToriApartDoNotCollide) {
  Pose side;  // same plane, outer rims 0.1 apart
  side.translation = {1.5, 0, 0};
  EXPECT_TRUE(peerPairs(GetParam(), torusPair(side))[0].empty());
  // Linked like chain links: the tube axes stay 0.5 apart everywhere, so the tubes (0.2 each)
  // are 0.1 apart everywhere while the bounding boxes overlap. A rotation applied wrongly would
  // make them cross.
  EXPECT_TRUE(peerPairs(GetParam(), torusPair(quarterTurned(0.5)))[0].empty());
}

// Resting contact, as in the piles of env1 and env2, a micrometre either side of touching: no
// contact margin may report the gap, and no tolerance may drop the shallow penetration.
TEST_P(PeerTest, ShallowContactOnAPlane) {
  for (const double gap : {1e-6, -1e-6}) {
    const auto scene = torusOnPlane(gap);
    const auto expected = GroundTruth(scene.scene).compute(scene.frames[0]).collidingPairs;
    ASSERT_EQ(expected.size(), gap < 0 ? 1u : 0u) << "gap " << gap;
    EXPECT_EQ(peerPairs(GetParam(), scene)[0], expected) << GetParam() << " gap " << gap;
  }
}

TEST_P(PeerTest, RandomToriAgreeWithGroundTruth) {
  const auto scene = testing::randomTori(40, 1.2, 4, 21);
  GroundTruth truth(scene.scene);
  const auto found = peerPairs(GetParam(), scene);
  std::size_t truthPairs = 0;
  for (std::size_t f = 0; f < scene.frames.size(); ++f) {
    const auto expected = truth.compute(scene.frames[f]).collidingPairs;
    truthPairs += expected.size();
    EXPECT_EQ(found[f], expected) << GetParam() << " frame " << f;
  }
  EXPECT_GT(truthPairs, 0u);
}

// Every entry makes a detector of its own name; only the CPU peers make it without a culling
// strategy, and they never ask the backend they are offered.
TEST(DetectorRegistry, PeersAreDetectorsWithoutACullingStrategy) {
  const auto& registry = DetectorRegistry::builtin();
  Pose side;
  side.translation = {0.6, 0, 0};
  const auto scene = torusPair(side);
  ExactPhase exact(scene.scene);
  ScriptedVisibilityOracle oracle(
      [](const VisibilityCall&, std::span<const VisibilityCall>) { return false; });
  oracle.attachScene(scene.scene);
  std::size_t peers = 0;
  for (const auto& name : registry.names()) {
    const bool peer = registry.kind(name) == DetectorRegistry::Kind::CpuPeer;
    peers += peer;
    if (peer) {
      EXPECT_THROW((void)registry.create(name, {}), InputError) << name;
    } else {
      EXPECT_THROW((void)registry.createPeer(name, {}), InputError) << name;
    }
    auto detector = registry.createDetector(name, {}, oracle, exact);
    EXPECT_EQ(detector->name(), name);
    detector->attach(scene.scene);
    const std::size_t asked = oracle.log().size();
    const DetectedFrame d = detector->detect({scene.frames[0], 0});
    EXPECT_EQ(d.culled.has_value(), !peer) << name;
    if (peer) {
      EXPECT_EQ(oracle.log().size(), asked) << name;
    }
  }
  EXPECT_EQ(peers, registry.names(DetectorRegistry::Kind::CpuPeer).size());
  EXPECT_GT(peers, 0u);
}

INSTANTIATE_TEST_SUITE_P(
    Peers, PeerTest,
    ::testing::ValuesIn(DetectorRegistry::builtin().names(DetectorRegistry::Kind::CpuPeer)),
    [](const auto& param) { return param.param; });

}  // namespace
}  // namespace cdb
