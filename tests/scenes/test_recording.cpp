// Pose recordings: the hash, the scenario fingerprint, recording a simulation, and the file format
// (round trip, atomic writes, and a clear error for every way a file can be wrong).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "core/Errors.h"
#include "scenes/PoseRecording.h"
#include "scenes/RigidBodySimulation.h"
#include "tests/scenes/DynamicsTestScenes.h"

namespace cdb {
namespace {

using namespace dynamics_test;
namespace fs = std::filesystem;

class PoseRecordingFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("cdbench-recording-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  [[nodiscard]] fs::path file(const std::string& name) const { return dir_ / name; }

  static std::vector<char> bytesOf(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  static void writeBytes(const fs::path& path, const std::vector<char>& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
  }
  // The message of the InputError that reading `path` throws.
  static std::string readError(const fs::path& path) {
    try {
      (void)readPoseRecording(path);
    } catch (const InputError& error) {
      return error.what();
    }
    return "(no error)";
  }

  fs::path dir_;
};

// Two frames of three objects with distinct, exactly representable values.
PoseRecording smallRecording() {
  PoseRecording r;
  r.environment = "env-test";
  r.fingerprint = 0x0123456789abcdefULL;
  r.seed = 42;
  r.objectCount = 3;
  for (int i = 0; i < 6; ++i) {
    Pose p;
    p.translation = Eigen::Vector3d(i, -0.5 * i, 0.25 + i);
    p.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.1 * i, Eigen::Vector3d::UnitY()));
    r.poses.push_back(p);
  }
  return r;
}

bool samePoses(const std::vector<Pose>& a, const std::vector<Pose>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].translation != b[i].translation || a[i].rotation.coeffs() != b[i].rotation.coeffs()) {
      return false;
    }
  }
  return true;
}

// Header bytes besides the environment name (docs/pose-recording.md).
constexpr std::size_t kHeaderWithoutName = 8 + 4 + 4 + 8 + 8 + 4 + 4 + 8;

TEST(PoseRecording, HashIsFnv1aOverTranslationThenWxyz) {
  PoseRecording r;
  r.objectCount = 1;
  Pose p;
  p.translation = Eigen::Vector3d(1, 2, 3);
  p.rotation = Eigen::Quaterniond(0.5, -0.5, 0.5, -0.5);
  r.poses = {p};
  // The reference: FNV-1a 64 over the little-endian bytes of 1, 2, 3, 0.5, -0.5, 0.5, -0.5.
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (double v : {1.0, 2.0, 3.0, 0.5, -0.5, 0.5, -0.5}) {
    unsigned char bytes[8];
    std::memcpy(bytes, &v, 8);  // the machines the project runs on are little-endian
    for (unsigned char b : bytes) h = (h ^ b) * 0x100000001b3ULL;
  }
  EXPECT_EQ(r.hash(), h);
  r.poses[0].rotation.x() = std::nextafter(-0.5, 0.0);
  EXPECT_NE(r.hash(), h) << "one bit must change the hash";
}

TEST(PoseRecording, FingerprintCoversWhatDeterminesFramesOnly) {
  const ScenarioConfig base = cubeScenario(5);
  const SceneGeometry scene = sceneFor(base);
  const std::uint64_t f = scenarioFingerprint(base, scene);

  ScenarioConfig same = base;
  same.description = "another description";
  same.sweep.resolutions = {500, 600};
  same.sweep.repeats = 10;
  same.culling.visibility.conservative = false;
  same.seed = 99;  // the seed travels beside the fingerprint
  same.sourcePath = "elsewhere.yaml";
  EXPECT_EQ(scenarioFingerprint(same, scene), f);

  const auto differs = [&](const std::function<void(ScenarioConfig&)>& change) {
    ScenarioConfig c = base;
    change(c);
    return scenarioFingerprint(c, sceneFor(c)) != f;
  };
  EXPECT_TRUE(differs([](ScenarioConfig& c) { c.dynamics.timeStep = 0.005; }));
  EXPECT_TRUE(differs([](ScenarioConfig& c) { c.dynamics.frames += 1; }));
  EXPECT_TRUE(differs([](ScenarioConfig& c) { c.dynamics.gravity[1] = -1; }));
  EXPECT_TRUE(differs([](ScenarioConfig& c) { c.bodies[0].count = 6; }));
  EXPECT_TRUE(differs([](ScenarioConfig& c) { c.bodies[0].name = "ring"; }));
  EXPECT_TRUE(differs([](ScenarioConfig& c) { c.bodies[0].density = 2; }));
  EXPECT_TRUE(differs([](ScenarioConfig& c) { c.bodies[0].mesh.minorRadius = 0.1; }));
  EXPECT_TRUE(differs([](ScenarioConfig& c) { c.bodies[0].placement->speedMax = 4; }));
  EXPECT_TRUE(differs([](ScenarioConfig& c) { c.bodies[0].collision = CollisionProxy::Sphere; }));
  // A field the torus does not use changes nothing.
  EXPECT_FALSE(differs([](ScenarioConfig& c) { c.bodies[0].mesh.planeSize = 3; }));

  SceneGeometry finer = scene;
  finer.meshes[0] = makeTorus(0.5, 0.2, 30, 30);
  EXPECT_NE(scenarioFingerprint(base, finer), f);
  // Another copy of a mesh: same counts and bounds, one vertex moved inside them (the npm PLY and
  // the OBJ of the dragon differ so), or one triangle's corners in another order.
  SceneGeometry moved = scene;
  const auto box = scene.meshes[0].bounds();
  const auto inside = std::find_if(
      moved.meshes[0].vertices.begin(), moved.meshes[0].vertices.end(), [&](const auto& v) {
        return ((v.template cast<double>().array() > box.min().array()) &&
                (v.template cast<double>().array() < box.max().array()))
            .all();
      });
  ASSERT_NE(inside, moved.meshes[0].vertices.end());
  *inside *= 0.999f;
  EXPECT_EQ(moved.meshes[0].bounds().min(), box.min());
  EXPECT_EQ(moved.meshes[0].bounds().max(), box.max());
  EXPECT_NE(scenarioFingerprint(base, moved), f);
  SceneGeometry turned = scene;
  std::swap(turned.meshes[0].triangles[0][0], turned.meshes[0].triangles[0][1]);
  EXPECT_NE(scenarioFingerprint(base, turned), f);
}

TEST(PoseRecording, RecordsFramesAfterWarmUp) {
  ScenarioConfig config = cubeScenario(6);
  config.dynamics.warmupFrames = 3;
  config.dynamics.frames = 5;
  const SceneGeometry scene = sceneFor(config);
  const PoseRecording recording = recordSimulation(config, scene, 5);
  EXPECT_EQ(recording.environment, config.environment);
  EXPECT_EQ(recording.fingerprint, scenarioFingerprint(config, scene));
  EXPECT_EQ(recording.seed, 5u);
  EXPECT_EQ(recording.objectCount, 6u);
  ASSERT_EQ(recording.frameCount(), 5u);

  // Recorded frame 0 is the state after warm-up plus one frame.
  RigidBodySimulation simulation(config, scene, 5);
  for (int f = 0; f < 4; ++f) simulation.stepFrame();
  const std::vector<Pose> expected(simulation.poses().begin(), simulation.poses().end());
  const auto frame0 = recording.frame(0);
  EXPECT_TRUE(samePoses(std::vector<Pose>(frame0.begin(), frame0.end()), expected));
}

TEST_F(PoseRecordingFile, SimulationRoundTripsBitForBit) {
  ScenarioConfig config = cubeScenario(8);
  config.dynamics.frames = 30;
  const SceneGeometry scene = sceneFor(config);
  const PoseRecording recorded = recordSimulation(config, scene, 3);
  writePoseRecording(recorded, file("run.cdbpose"));
  const PoseRecording read = readPoseRecording(file("run.cdbpose"));
  EXPECT_EQ(read.environment, recorded.environment);
  EXPECT_EQ(read.fingerprint, recorded.fingerprint);
  EXPECT_EQ(read.seed, recorded.seed);
  EXPECT_EQ(read.objectCount, recorded.objectCount);
  EXPECT_EQ(read.frameCount(), 30u);
  EXPECT_TRUE(samePoses(read.poses, recorded.poses));
  EXPECT_EQ(read.hash(), recorded.hash());
  // Nothing but the recording is left in the directory (no temporary file).
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

TEST_F(PoseRecordingFile, HeaderIsLaidOutAsDocumented) {
  const PoseRecording r = smallRecording();
  writePoseRecording(r, file("small.cdbpose"));
  const std::vector<char> bytes = bytesOf(file("small.cdbpose"));
  const std::size_t header = kHeaderWithoutName + r.environment.size();
  ASSERT_EQ(bytes.size(), header + 6 * 7 * 8);
  EXPECT_EQ(std::string(bytes.data(), 8), "CDBPOSE1");
  EXPECT_EQ(bytes[8], 1);                                        // version 1, little-endian
  EXPECT_EQ(bytes[12], 8);                                       // name length
  EXPECT_EQ(std::string(bytes.data() + 16, 8), "env-test");      // name
  EXPECT_EQ(std::uint8_t(bytes[24]), 0xef);                      // fingerprint, low byte first
  EXPECT_EQ(bytes[32], 42);                                      // seed
  EXPECT_EQ(bytes[40], 3);                                       // objects
  EXPECT_EQ(bytes[44], 2);                                       // frames
  std::uint64_t hash;
  std::memcpy(&hash, bytes.data() + 48, 8);
  EXPECT_EQ(hash, r.hash());
  double firstDouble;  // frame 0, object 0, translation x
  std::memcpy(&firstDouble, bytes.data() + header, 8);
  EXPECT_EQ(firstDouble, 0.0);
  double secondPoseY;  // frame 0, object 1, translation y
  std::memcpy(&secondPoseY, bytes.data() + header + 56 + 8, 8);
  EXPECT_EQ(secondPoseY, -0.5);
  double lastDouble;  // frame 1, object 2, rotation z
  std::memcpy(&lastDouble, bytes.data() + bytes.size() - 8, 8);
  EXPECT_EQ(lastDouble, r.poses[5].rotation.z());
}

TEST_F(PoseRecordingFile, EmptyRecordingRoundTrips) {
  PoseRecording r;
  r.environment = "env3";
  r.objectCount = 200;
  writePoseRecording(r, file("empty.cdbpose"));
  const PoseRecording read = readPoseRecording(file("empty.cdbpose"));
  EXPECT_EQ(read.objectCount, 200u);
  EXPECT_EQ(read.frameCount(), 0u);
}

TEST_F(PoseRecordingFile, WriteReplacesAnExistingFile) {
  PoseRecording r = smallRecording();
  writePoseRecording(r, file("x.cdbpose"));
  r.seed = 7;
  writePoseRecording(r, file("x.cdbpose"));
  EXPECT_EQ(readPoseRecording(file("x.cdbpose")).seed, 7u);
}

TEST_F(PoseRecordingFile, UnwritablePlaceIsRunErrorAndLeavesNothing) {
  const fs::path target = file("missing-dir") / "run.cdbpose";
  try {
    writePoseRecording(smallRecording(), target);
    FAIL() << "expected RunError";
  } catch (const RunError& error) {
    EXPECT_PRED_FORMAT2(::testing::IsSubstring, target.string() + ": cannot write pose recording",
                        error.what());
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 0);
}

TEST_F(PoseRecordingFile, PartialFramesAreRefusedOnWrite) {
  PoseRecording r = smallRecording();
  r.poses.pop_back();
  EXPECT_THROW(writePoseRecording(r, file("bad.cdbpose")), RunError);
  EXPECT_FALSE(fs::exists(file("bad.cdbpose")));
}

TEST_F(PoseRecordingFile, MissingFileIsInputErrorNamingIt) {
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, file("nope.cdbpose").string() + ": cannot open",
                      readError(file("nope.cdbpose")));
}

TEST_F(PoseRecordingFile, WrongMagicIsNotARecording) {
  writeBytes(file("text.cdbpose"), {'h', 'e', 'l', 'l', 'o', ' ', 'w', 'o', 'r', 'l', 'd', '\n'});
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, file("text.cdbpose").string() + ": not a pose recording",
                      readError(file("text.cdbpose")));
  writeBytes(file("tiny.cdbpose"), {'C', 'D'});
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "not a pose recording", readError(file("tiny.cdbpose")));
}

TEST_F(PoseRecordingFile, OtherVersionIsUnsupported) {
  writePoseRecording(smallRecording(), file("v.cdbpose"));
  std::vector<char> bytes = bytesOf(file("v.cdbpose"));
  bytes[8] = 2;
  writeBytes(file("v.cdbpose"), bytes);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring,
                      file("v.cdbpose").string() + ": unsupported pose recording version 2",
                      readError(file("v.cdbpose")));
}

TEST_F(PoseRecordingFile, TruncatedFileSaysWhatIsMissing) {
  writePoseRecording(smallRecording(), file("t.cdbpose"));
  std::vector<char> bytes = bytesOf(file("t.cdbpose"));
  bytes.resize(bytes.size() - 100);
  writeBytes(file("t.cdbpose"), bytes);
  const std::string dataBytes = std::to_string(6 * 56 - 100);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring,
                      file("t.cdbpose").string() + ": truncated: expected 2 frames of 3 objects, found " +
                          dataBytes + " of 336 bytes",
                      readError(file("t.cdbpose")));

  bytes.resize(20);  // inside the header
  writeBytes(file("t.cdbpose"), bytes);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, file("t.cdbpose").string() + ": truncated",
                      readError(file("t.cdbpose")));
}

TEST_F(PoseRecordingFile, TrailingBytesAreRefused) {
  writePoseRecording(smallRecording(), file("long.cdbpose"));
  std::vector<char> bytes = bytesOf(file("long.cdbpose"));
  bytes.push_back(0);
  writeBytes(file("long.cdbpose"), bytes);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "1 unexpected bytes after the last frame",
                      readError(file("long.cdbpose")));
}

TEST_F(PoseRecordingFile, NaNPoseNamesFrameAndObject) {
  PoseRecording r = smallRecording();
  r.poses[1 * 3 + 2].translation.y() = std::numeric_limits<double>::quiet_NaN();
  writePoseRecording(r, file("nan.cdbpose"));
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, file("nan.cdbpose").string() + ": NaN in frame 1 object 2",
                      readError(file("nan.cdbpose")));
}

TEST_F(PoseRecordingFile, CorruptedPoseDataFailsTheChecksum) {
  writePoseRecording(smallRecording(), file("c.cdbpose"));
  std::vector<char> bytes = bytesOf(file("c.cdbpose"));
  bytes[bytes.size() - 20] ^= 0x01;  // one bit of a mantissa: still a finite number
  writeBytes(file("c.cdbpose"), bytes);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "does not match the checksum", readError(file("c.cdbpose")));
}

}  // namespace
}  // namespace cdb
