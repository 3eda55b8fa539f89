// A recorded run replays to the same answers through the interface and on the draw floor.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/Errors.h"
#include "culling/visibility/GlDrawFloor.h"
#include "culling/visibility/RecordingBackend.h"
#include "scenes/ProceduralMeshes.h"
#include "tests/visibility/GlTestSupport.h"

namespace cdb {
namespace {

// A row of tori, every other one dropped into its neighbour, and a CULLIDE-like frame: two passes
// along x and z, each object tested then written (with `gated`, each pass-2 test gated by the same
// object's pass-1 test), a box pass and a triangle write.
struct ToriRun {
  SceneGeometry scene;
  std::vector<Pose> poses;

  ToriRun() {
    scene.meshes.push_back(makeTorus(1.0, 0.3, 20, 20));
    for (int i = 0; i < 6; ++i) scene.objects.push_back({0, false, ""});
    for (int i = 0; i < 6; ++i) {
      Pose p;
      p.translation = Eigen::Vector3d(2.2 * i - (i % 2) * 0.9, 0.1 * i, 0.0);
      p.rotation = Eigen::AngleAxisd(0.4 * i, Eigen::Vector3d::UnitX());
      poses.push_back(p);
    }
  }

  // The scene attached to `recording`, then one frame.
  void record(RecordingBackend& recording, bool gated = false) const {
    recording.attachScene(scene);
    frame(recording, gated);
  }

  void frame(VisibilityBackend& backend, bool gated = false) const {
    backend.setPoses(poses);
    const Aabb bounds(Eigen::Vector3d(-2, -2, -2), Eigen::Vector3d(14, 2.5, 2));
    QueryIndex first[6];
    for (const Eigen::Vector3d axis : {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ()}) {
      backend.beginPass({axis, bounds, 128}, DepthUse::SharedFirst);
      for (ObjectId o = 0; o < 6; ++o) {
        first[o] = backend.queryRange(test::wholeOf(scene, o));
        backend.writeRange(test::wholeOf(scene, o));
      }
      backend.beginPass({-axis, bounds, 128}, DepthUse::SharedSecond);
      for (ObjectId o = 6; o-- > 0;) {
        const QueryIndex second = backend.queryRange(test::wholeOf(scene, o));
        if (gated) backend.gateAnswers(second, first[o], 1);
        backend.writeRange(test::wholeOf(scene, o));
      }
    }
    backend.beginPass({Eigen::Vector3d(1, 1, 1).normalized(), bounds, 64}, DepthUse::Fresh);
    OrientedBox box;
    box.halfExtents = Eigen::Vector3d(1.3, 0.3, 1.3);
    const std::uint32_t some[] = {0, 1, 2, 3, 100, 101, 400};
    backend.writeTriangles(2, some);
    for (ObjectId o = 0; o < 6; ++o) {
      backend.queryBox(o, box);
      backend.writeBox(o, box);
    }
    std::vector<std::uint8_t> answers;
    backend.fetchResults(answers);
  }
};

TEST(RecordingBackend, ForwardsLogsAndReplays) {
  const ToriRun run;
  GlOcclusionQueryBackend gl(test::sharedGlContext());
  RecordingBackend recording(gl);
  EXPECT_EQ(recording.name(), "recording:gl-queries");
  run.record(recording);
  const VisibilityCounters recorded = recording.counters();
  EXPECT_EQ(recorded.queries, 30u);
  EXPECT_EQ(recorded.draws, 61u);
  EXPECT_EQ(recorded.passes, 5u);
  EXPECT_EQ(recorded.depthClears, 3u);
  EXPECT_EQ(recorded.fetches, 1u);
  const std::vector<VisibilityCall>& ops = recording.ops();
  ASSERT_FALSE(ops.empty());
  EXPECT_EQ(ops.front().kind, VisibilityCall::Kind::AttachScene);
  EXPECT_EQ(ops.back().kind, VisibilityCall::Kind::FetchResults);
  const std::vector<std::uint8_t> answers = ops.back().answers;
  ASSERT_EQ(answers.size(), 30u);
  // The dropped-in tori collide with their neighbours: not everything is fully visible.
  EXPECT_LT(std::count(answers.begin(), answers.end(), 1), 30);

  GlOcclusionQueryBackend again(test::sharedGlContext());
  RecordingBackend second(again);
  replayOps(second, ops);
  EXPECT_EQ(second.ops().back().answers, answers);
  EXPECT_EQ(again.counters().draws, recorded.draws);
}

TEST(GlDrawFloor, ReplaysTheSameWork) {
  const ToriRun run;
  GlOcclusionQueryBackend gl(test::sharedGlContext());
  RecordingBackend recording(gl);
  run.record(recording);
  GlDrawFloor floor(test::sharedGlContext());
  const FloorTiming t = floor.replay(recording.ops(), 2);
  EXPECT_TRUE(t.answersMatch);
  EXPECT_EQ(t.queries, 30u);
  EXPECT_EQ(t.draws, 61u);
  EXPECT_EQ(t.passes, 5u);
  EXPECT_EQ(t.fetches, 1u);
  EXPECT_GT(t.bestSeconds, 0.0);
  EXPECT_LE(t.bestSeconds, t.meanSeconds);
}

// Gates are logged, replayed through the interface, and applied by the floor to its own answers.
TEST(GlDrawFloor, GatedRecordingReplaysGated) {
  const ToriRun run;
  GlOcclusionQueryBackend gl(test::sharedGlContext());
  RecordingBackend plain(gl);
  run.record(plain);
  RecordingBackend gated(gl);
  run.record(gated, true);
  const std::vector<std::uint8_t>& answers = gated.ops().back().answers;
  ASSERT_EQ(answers.size(), plain.ops().back().answers.size());
  EXPECT_NE(answers, plain.ops().back().answers) << "some object visible in pass 2 only";
  EXPECT_EQ(std::count_if(gated.ops().begin(), gated.ops().end(),
                          [](const VisibilityCall& c) {
                            return c.kind == VisibilityCall::Kind::GateAnswers;
                          }),
            12);

  GlOcclusionQueryBackend again(test::sharedGlContext());
  RecordingBackend second(again);
  replayOps(second, gated.ops());
  EXPECT_EQ(second.ops().back().answers, answers);
  GlDrawFloor floor(test::sharedGlContext());
  EXPECT_TRUE(floor.replay(gated.ops(), 1).answersMatch);
}

TEST(GlDrawFloor, RawModeRecordingReplaysInRawMode) {
  const ToriRun run;
  const VisibilityOptions raw{false, 1e-5};
  GlOcclusionQueryBackend gl(test::sharedGlContext(), raw);
  RecordingBackend recording(gl);
  run.record(recording);
  GlDrawFloor floor(test::sharedGlContext(), raw);
  EXPECT_TRUE(floor.replay(recording.ops(), 1).answersMatch);
}

TEST(GlDrawFloor, PreparedRecordingsReplayAgainAndAgainEachOnItsScene) {
  const ToriRun run;
  ToriRun shifted;
  shifted.scene.meshes[0] = makeTorus(1.25, 0.25, 24, 20);  // wider tori: more of them touch
  GlOcclusionQueryBackend gl(test::sharedGlContext());
  RecordingBackend first(gl);
  run.record(first);
  RecordingBackend second(gl);
  shifted.record(second);
  // A replay drawing one recording's commands on the other scene would answer differently.
  ASSERT_NE(first.ops().back().answers, second.ops().back().answers);

  GlDrawFloor floor(test::sharedGlContext());
  GlDrawFloor::Prepared a = floor.prepare(first.ops());
  GlDrawFloor::Prepared b = floor.prepare(second.ops());
  EXPECT_EQ(a.queries(), 30u);
  EXPECT_EQ(a.draws(), 61u);
  EXPECT_EQ(a.passes(), 5u);
  EXPECT_EQ(a.fetches(), 1u);
  // Alternating: each replay brings its own scene back into the floor's buffers.
  for (int i = 0; i < 2; ++i) {
    floor.replayOnce(a);
    EXPECT_TRUE(a.answersMatch());
    floor.replayOnce(b);
    EXPECT_TRUE(b.answersMatch());
  }
}

TEST(GlDrawFloor, RecordingWithoutSceneIsRejected) {
  GlDrawFloor floor(test::sharedGlContext());
  std::vector<VisibilityCall> ops(1);
  EXPECT_THROW(floor.replay(ops), InputError);
}

}  // namespace
}  // namespace cdb
