// The backend contract: what a fully-visible test means, on every registered backend, in both
// modes: an object behind what was written is not fully visible, one in front or beside it is;
// the DepthUse passes; boxes; batches answer each piece; misuse is reported.
#include <gtest/gtest.h>

#include <numeric>
#include <tuple>

#include "core/Errors.h"
#include "scenes/ProceduralMeshes.h"
#include "tests/common/BoxMeshes.h"
#include "tests/visibility/GlTestSupport.h"

namespace cdb {
namespace {

using test::squareMesh;
using test::wholeOf;

// Backend, conservative mode.
using BackendAndMode = std::tuple<std::string, bool>;

struct ParamName {
  std::string operator()(const testing::TestParamInfo<BackendAndMode>& info) const {
    return test::testNamePart(std::get<0>(info.param)) +
           (std::get<1>(info.param) ? "_Conservative" : "_Raw");
  }
};

class OcclusionSemantics : public testing::TestWithParam<BackendAndMode> {
 protected:
  // Squares of half size 1: A at z = 0, B at z = 2 (behind A along +z), C at z = -2 (in front),
  // D beside A in the image (x = 5), E coplanar with A.
  void SetUp() override {
    scene_ = test::sceneOf({squareMesh(0, 0, 0, 1), squareMesh(0, 0, 2, 1), squareMesh(0, 0, -2, 1),
                            squareMesh(5, 0, 0, 1), squareMesh(0.5f, 0, 0, 1)});
    backend_ = VisibilityBackendRegistry::builtin().create(
        std::get<0>(GetParam()), test::sharedBackendResources(),
        VisibilityOptions{std::get<1>(GetParam()), 1e-5});
    backend_->attachScene(scene_);
    backend_->setPoses(test::identityPoses(scene_.objectCount()));
  }

  ViewSpec view(const Eigen::Vector3d& direction, int resolution = 64) const {
    return {direction, Aabb(Eigen::Vector3d(-2, -2, -3), Eigen::Vector3d(7, 2, 3)), resolution};
  }

  // Writes `written` then tests each of `tested` in one Fresh pass; returns the answers.
  std::vector<std::uint8_t> afterWriting(
      ObjectId written, std::vector<ObjectId> tested,
      const Eigen::Vector3d& direction = Eigen::Vector3d::UnitZ()) {
    backend_->beginPass(view(direction), DepthUse::Fresh);
    backend_->writeRange(wholeOf(scene_, written));
    for (ObjectId o : tested) backend_->queryRange(wholeOf(scene_, o));
    std::vector<std::uint8_t> answers;
    backend_->fetchResults(answers);
    return answers;
  }

  SceneGeometry scene_;
  std::unique_ptr<VisibilityBackend> backend_;
};

TEST_P(OcclusionSemantics, BehindIsOccludedFrontAndBesideAreVisible) {
  const auto answers = afterWriting(0, {1, 2, 3});
  ASSERT_EQ(answers.size(), 3u);
  EXPECT_EQ(answers[0], 0) << "B behind A";
  EXPECT_EQ(answers[1], 1) << "C in front of A";
  EXPECT_EQ(answers[2], 1) << "D beside A";
}

TEST_P(OcclusionSemantics, ViewDirectionDecidesWhatIsBehind) {
  const auto answers = afterWriting(0, {1, 2}, -Eigen::Vector3d::UnitZ());
  EXPECT_EQ(answers[0], 1) << "B is in front when looking along -z";
  EXPECT_EQ(answers[1], 0) << "C is behind when looking along -z";
}

TEST_P(OcclusionSemantics, CoplanarOverlapIsNotFullyVisible) {
  EXPECT_EQ(afterWriting(0, {4})[0], 0);
}

TEST_P(OcclusionSemantics, NothingWrittenMeansFullyVisible) {
  backend_->beginPass(view(Eigen::Vector3d::UnitZ()), DepthUse::Fresh);
  for (ObjectId o = 0; o < scene_.objectCount(); ++o) backend_->queryRange(wholeOf(scene_, o));
  std::vector<std::uint8_t> answers;
  backend_->fetchResults(answers);
  EXPECT_EQ(answers, std::vector<std::uint8_t>(scene_.objectCount(), 1));
}

TEST_P(OcclusionSemantics, SharedPassesShareOneClear) {
  // Pass 1 writes A and C; pass 2 (no clear) must not see them, and sees its own writes.
  backend_->beginPass(view(Eigen::Vector3d::UnitZ()), DepthUse::SharedFirst);
  backend_->writeRange(wholeOf(scene_, 0));
  backend_->writeRange(wholeOf(scene_, 2));
  const QueryIndex firstPassB = backend_->queryRange(wholeOf(scene_, 1));
  backend_->beginPass(view(-Eigen::Vector3d::UnitZ()), DepthUse::SharedSecond);
  const QueryIndex secondPassA = backend_->queryRange(wholeOf(scene_, 0));
  const QueryIndex secondPassB = backend_->queryRange(wholeOf(scene_, 1));
  backend_->writeRange(wholeOf(scene_, 1));  // B is nearest along -z
  const QueryIndex behindB = backend_->queryRange(wholeOf(scene_, 0));
  const QueryIndex beside = backend_->queryRange(wholeOf(scene_, 3));
  std::vector<std::uint8_t> answers;
  backend_->fetchResults(answers);
  ASSERT_EQ(answers.size(), 5u);
  EXPECT_EQ(answers[firstPassB], 0) << "pass 1: B behind A";
  EXPECT_EQ(answers[secondPassA], 1) << "pass 2: pass-1 leftovers do not occlude";
  EXPECT_EQ(answers[secondPassB], 1) << "pass 2: pass-1 leftovers do not occlude";
  EXPECT_EQ(answers[behindB], 0) << "pass 2: A behind B written in pass 2";
  EXPECT_EQ(answers[beside], 1) << "pass 2: D beside";
  const VisibilityCounters c = backend_->counters();
  EXPECT_EQ(c.passes, 2u);
  EXPECT_EQ(c.depthClears, 1u);
  EXPECT_EQ(c.queries, 5u);
  EXPECT_EQ(c.draws, 8u);
  EXPECT_EQ(c.fetches, 1u);
}

TEST_P(OcclusionSemantics, SharedSecondPassAloneIsRejected) {
  backend_->beginPass(view(Eigen::Vector3d::UnitZ()), DepthUse::Fresh);
  EXPECT_THROW(backend_->beginPass(view(Eigen::Vector3d::UnitZ()), DepthUse::SharedSecond),
               RunError);
}

TEST_P(OcclusionSemantics, BoxesQueryAndWrite) {
  OrientedBox slab;  // a thin box around A's square
  slab.halfExtents = Eigen::Vector3d(1, 1, 0.05);
  OrientedBox far = slab;
  far.center = Eigen::Vector3d(0, 0, 2.5);
  backend_->beginPass(view(Eigen::Vector3d::UnitZ()), DepthUse::Fresh);
  backend_->writeBox(0, slab);
  const QueryIndex farBox = backend_->queryBox(3, far);  // object 3's frame is the world frame too
  const QueryIndex b = backend_->queryRange(wholeOf(scene_, 1));
  const QueryIndex c = backend_->queryRange(wholeOf(scene_, 2));
  far.center = Eigen::Vector3d(0, 0, -2.5);
  const QueryIndex nearBox = backend_->queryBox(1, far);
  std::vector<std::uint8_t> answers;
  backend_->fetchResults(answers);
  EXPECT_EQ(answers[farBox], 0);
  EXPECT_EQ(answers[b], 0);
  EXPECT_EQ(answers[c], 1);
  EXPECT_EQ(answers[nearBox], 1);
}

TEST_P(OcclusionSemantics, PosesMoveObjects) {
  std::vector<Pose> poses = test::identityPoses(scene_.objectCount());
  poses[1].translation = Eigen::Vector3d(5, 0, 0);  // B moves beside A
  backend_->setPoses(poses);
  EXPECT_EQ(afterWriting(0, {1})[0], 1);
  poses[1].translation = Eigen::Vector3d(0, 0, 0);
  poses[1].rotation = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX());  // B tilted, still behind
  backend_->setPoses(poses);
  EXPECT_EQ(afterWriting(0, {1})[0], 0);
}

TEST_P(OcclusionSemantics, WriteTrianglesIsOneDraw) {
  backend_->beginPass(view(Eigen::Vector3d::UnitZ()), DepthUse::Fresh);
  const std::uint32_t second[] = {1};
  backend_->writeTriangles(0, second);  // only the upper-left half of A
  backend_->resetCounters();
  const std::uint32_t both[] = {1, 0};
  backend_->writeTriangles(0, both);
  EXPECT_EQ(backend_->counters().draws, 1u);
  EXPECT_EQ(backend_->counters().trianglesDrawn, 2u);
  const std::uint32_t bad[] = {2};
  EXPECT_THROW(backend_->writeTriangles(0, bad), RunError);
}

TEST_P(OcclusionSemantics, MisuseIsReported) {
  EXPECT_THROW(backend_->queryRange(wholeOf(scene_, 0)), RunError) << "outside a pass";
  backend_->beginPass(view(Eigen::Vector3d::UnitZ()), DepthUse::Fresh);
  EXPECT_THROW(backend_->queryRange({99, 0, 1}), RunError);
  EXPECT_THROW(backend_->queryRange({0, 1, 5}), RunError);
  EXPECT_THROW(backend_->beginPass(view(Eigen::Vector3d::UnitZ(), 0), DepthUse::Fresh), InputError);
  EXPECT_THROW(backend_->beginPass(view(Eigen::Vector3d::UnitZ(), 1000000), DepthUse::Fresh),
               InputError);
  EXPECT_THROW(backend_->setPoses(test::identityPoses(2)), RunError);
}

TEST_P(OcclusionSemantics, BatchesAnswerEachPieceAgainstWhatWasWrittenBefore) {
  OrientedBox behind;  // boxes of object 3 (world frame): behind A, in front of A, beside A
  behind.halfExtents = Eigen::Vector3d(0.5, 0.5, 0.1);
  behind.center = Eigen::Vector3d(0, 0, 2.5);
  OrientedBox front = behind;
  front.center = Eigen::Vector3d(0, 0, -2.5);
  OrientedBox beside = behind;
  beside.center = Eigen::Vector3d(5, 0, 0.5);
  const OrientedBox boxes[] = {behind, front, beside};
  const std::uint32_t bothOfC[] = {1, 0};

  backend_->beginPass(view(Eigen::Vector3d::UnitZ()), DepthUse::Fresh);
  backend_->writeRange(wholeOf(scene_, 0));
  const QueryIndex triangles = backend_->queryTriangles(wholeOf(scene_, 1));  // B: behind A
  // C: in front. Its two triangles share an edge at equal depth: had the first been written
  // before the second was tested, the second would not be fully visible.
  const QueryIndex listed = backend_->queryTriangles(2, bothOfC);
  const QueryIndex boxAnswers = backend_->queryBoxes(3, boxes);
  EXPECT_EQ(backend_->queryTriangles(3, {}), kNoQuery);
  EXPECT_EQ(backend_->queryBoxes(3, {}), kNoQuery);
  const QueryIndex coplanarE = backend_->queryTriangles(wholeOf(scene_, 4));
  backend_->writeBoxes(3, std::span<const OrientedBox>(boxes + 1, 1));         // the front box
  const QueryIndex afterWrite = backend_->queryTriangles(wholeOf(scene_, 2));  // C behind it now
  std::vector<std::uint8_t> answers;
  backend_->fetchResults(answers);
  ASSERT_EQ(answers.size(), 11u);
  EXPECT_EQ(listed, triangles + 2);
  EXPECT_EQ(boxAnswers, listed + 2);
  EXPECT_EQ(
      (std::vector<std::uint8_t>(answers.begin() + triangles, answers.begin() + triangles + 2)),
      (std::vector<std::uint8_t>{0, 0}))
      << "both triangles of B lie behind A";
  EXPECT_EQ(answers[listed], 1) << "C in front of A";
  EXPECT_EQ(answers[listed + 1], 1) << "pieces of one batch do not occlude each other";
  EXPECT_EQ(answers[boxAnswers], 0) << "box behind A";
  EXPECT_EQ(answers[boxAnswers + 1], 1) << "box in front of A";
  EXPECT_EQ(answers[boxAnswers + 2], 1) << "box beside A";
  EXPECT_EQ(answers[coplanarE], 0) << "each triangle of E overlaps A, coplanar";
  EXPECT_EQ(answers[coplanarE + 1], 0) << "each triangle of E overlaps A, coplanar";
  EXPECT_EQ(answers[afterWrite], 0) << "C behind the front box written after the batches";
  EXPECT_EQ(answers[afterWrite + 1], 0) << "C behind the front box written after the batches";
  EXPECT_EQ(backend_->counters().queries, 11u);
}

// A gated answer is fetched as the AND of its own and its gate's, whether or not the backend
// tests it: B behind A along +z (pass 1: occluded) but in front of it along -z (pass 2: visible),
// C the other way round, D beside A in both. CULLIDE's gating (each pass-2 test gated by the same
// piece's pass-1 test), and gates between different pieces.
TEST_P(OcclusionSemantics, GatedAnswersAreTheirOwnAndTheirGates) {
  backend_->beginPass(view(Eigen::Vector3d::UnitZ()), DepthUse::Fresh);
  backend_->writeRange(wholeOf(scene_, 0));
  const QueryIndex b1 = backend_->queryRange(wholeOf(scene_, 1));
  const QueryIndex c1 = backend_->queryRange(wholeOf(scene_, 2));
  const QueryIndex d1 = backend_->queryRange(wholeOf(scene_, 3));
  const QueryIndex bEach1 = backend_->queryTriangles(wholeOf(scene_, 1));
  const QueryIndex dEach1 = backend_->queryTriangles(3, std::vector<std::uint32_t>{0, 1});
  backend_->beginPass(view(-Eigen::Vector3d::UnitZ()), DepthUse::Fresh);
  backend_->writeRange(wholeOf(scene_, 0));
  const QueryIndex b2 = backend_->queryRange(wholeOf(scene_, 1));
  backend_->gateAnswers(b2, b1, 1);
  const QueryIndex c2 = backend_->queryRange(wholeOf(scene_, 2));
  backend_->gateAnswers(c2, c1, 1);
  const QueryIndex d2 = backend_->queryRange(wholeOf(scene_, 3));
  backend_->gateAnswers(d2, d1, 1);
  const QueryIndex bEach2 = backend_->queryTriangles(wholeOf(scene_, 1));
  backend_->gateAnswers(bEach2, bEach1, 2);
  const QueryIndex dEach2 = backend_->queryTriangles(3, std::vector<std::uint32_t>{0, 1});
  backend_->gateAnswers(dEach2, dEach1, 2);
  const QueryIndex bByD = backend_->queryRange(wholeOf(scene_, 1));  // another piece's gate
  backend_->gateAnswers(bByD, d1, 1);
  const QueryIndex dByB = backend_->queryRange(wholeOf(scene_, 3));
  backend_->gateAnswers(dByB, b1, 1);
  const QueryIndex bUngated = backend_->queryRange(wholeOf(scene_, 1));
  std::vector<std::uint8_t> answers;
  backend_->fetchResults(answers);
  ASSERT_EQ(answers.size(), 17u);
  EXPECT_EQ(answers[b1], 0) << "pass 1: B behind A";
  EXPECT_EQ(answers[c1], 1) << "pass 1: C in front of A";
  EXPECT_EQ(answers[bUngated], 1) << "pass 2: B in front of A";
  EXPECT_EQ(answers[b2], 0) << "B visible in pass 2, gated by its pass-1 answer";
  EXPECT_EQ(answers[c2], 0) << "C behind A in pass 2, whatever its gate";
  EXPECT_EQ(answers[d2], 1) << "D beside A in both passes";
  EXPECT_EQ(answers[bEach2], 0);
  EXPECT_EQ(answers[bEach2 + 1], 0);
  EXPECT_EQ(answers[dEach2], 1);
  EXPECT_EQ(answers[dEach2 + 1], 1);
  EXPECT_EQ(answers[bByD], 1) << "B visible in pass 2, its gate (D) visible";
  EXPECT_EQ(answers[dByB], 0) << "D visible, its gate (B in pass 1) not";
  // Gates hold until the fetch they belong to, no longer.
  backend_->beginPass(view(-Eigen::Vector3d::UnitZ()), DepthUse::Fresh);
  const QueryIndex again = backend_->queryRange(wholeOf(scene_, 1));
  backend_->fetchResults(answers);
  ASSERT_EQ(answers.size(), 1u);
  EXPECT_EQ(answers[again], 1);
}

// A gate goes by position in issue order, not by piece: two triangles, the first behind A and
// the second beside it, tested as {0, 1} in pass 1 (A written) and as {1, 0} in pass 2, each
// pass-2 answer gated by the pass-1 answer at its position. In pass 2 A is written again, or a
// square F between the two triangles (in front, covering neither: nothing decides the batch by
// bounds, and both triangles are visible).
TEST_P(OcclusionSemantics, GatesGoByIssuePosition) {
  Mesh two = squareMesh(0, 0, 1, 0.5f);  // behind A (z = 0)
  const Mesh beside = squareMesh(4, 0, 1, 0.5f);
  two.triangles.resize(1);
  two.vertices.insert(two.vertices.end(), beside.vertices.begin(), beside.vertices.end());
  two.triangles.push_back({4, 5, 6});
  const SceneGeometry scene =
      test::sceneOf({squareMesh(0, 0, 0, 1), two, squareMesh(2, 0, -1, 0.5f)});
  backend_->attachScene(scene);
  backend_->setPoses(test::identityPoses(scene.objectCount()));
  for (ObjectId second : {0u, 2u}) {
    SCOPED_TRACE(second == 0 ? "A written in pass 2" : "F written in pass 2");
    backend_->beginPass(view(Eigen::Vector3d::UnitZ()), DepthUse::Fresh);
    backend_->writeRange(wholeOf(scene, 0));
    const QueryIndex first = backend_->queryTriangles(1, std::vector<std::uint32_t>{0, 1});
    backend_->beginPass(view(Eigen::Vector3d::UnitZ()), DepthUse::Fresh);
    backend_->writeRange(wholeOf(scene, second));
    const QueryIndex swapped = backend_->queryTriangles(1, std::vector<std::uint32_t>{1, 0});
    backend_->gateAnswers(swapped, first, 2);
    const QueryIndex ungated = backend_->queryTriangles(1, std::vector<std::uint32_t>{1, 0});
    std::vector<std::uint8_t> answers;
    backend_->fetchResults(answers);
    ASSERT_EQ(answers.size(), 6u);
    const int zeroBehindA = second == 0 ? 0 : 1;  // triangle 0's pass-2 answer
    EXPECT_EQ(answers[first], 0) << "triangle 0 behind A";
    EXPECT_EQ(answers[first + 1], 1) << "triangle 1 beside A";
    EXPECT_EQ(answers[ungated], 1);
    EXPECT_EQ(answers[ungated + 1], zeroBehindA);
    EXPECT_EQ(answers[swapped], 0) << "triangle 1, gated by position 0 (triangle 0 in pass 1)";
    EXPECT_EQ(answers[swapped + 1], zeroBehindA)
        << "triangle 0, gated by position 1 (triangle 1 in pass 1)";
  }
}

TEST_P(OcclusionSemantics, GateMisuseIsRejected) {
  backend_->beginPass(view(Eigen::Vector3d::UnitZ()), DepthUse::Fresh);
  const QueryIndex first = backend_->queryTriangles(wholeOf(scene_, 1));
  const QueryIndex second = backend_->queryTriangles(wholeOf(scene_, 1));
  EXPECT_THROW(backend_->gateAnswers(first, second, 2), InputError) << "the gate after the gated";
  EXPECT_THROW(backend_->gateAnswers(first + 1, first, 2), InputError) << "overlapping";
  EXPECT_THROW(backend_->gateAnswers(second, kNoQuery, 2), InputError);
  backend_->gateAnswers(second, first, 0);      // nothing gated
  backend_->gateAnswers(second + 2, first, 2);  // not issued (yet): found at the fetch
  std::vector<std::uint8_t> answers;
  EXPECT_THROW(backend_->fetchResults(answers), RunError);
  backend_->beginPass(view(Eigen::Vector3d::UnitZ()), DepthUse::Fresh);
  backend_->queryRange(wholeOf(scene_, 1));
  backend_->fetchResults(answers);  // the failed fetch's gates are gone
  EXPECT_EQ(answers.size(), 1u);
}

// A batch over a whole closed mesh answers every triangle, those facing the viewer too: a backend
// may draw only the faces that decide a closed mesh's single answer (the farthest depth at a pixel
// lies on a face turned away), but each triangle of a batch is its own test, as when listed.
TEST_P(OcclusionSemantics, BatchOverAWholeClosedMeshAnswersEveryTriangle) {
  Mesh torus = makeTorus(0.5, 0.2, 12, 8);  // around z (its y axis turned onto z), behind A
  for (Eigen::Vector3f& v : torus.vertices) v = Eigen::Vector3f(v.x(), v.z(), v.y() + 1.f);
  const SceneGeometry scene = test::sceneOf({squareMesh(0, 0, 0, 1), torus});
  backend_->attachScene(scene);
  backend_->setPoses(test::identityPoses(scene.objectCount()));
  const std::size_t n = torus.triangleCount();
  std::vector<std::uint32_t> all(n);
  std::iota(all.begin(), all.end(), 0u);
  const bool conservative = std::get<1>(GetParam());
  for (bool written : {false, true}) {
    backend_->beginPass(view(Eigen::Vector3d::UnitZ()), DepthUse::Fresh);
    if (written) backend_->writeRange(wholeOf(scene, 0));
    const QueryIndex whole = backend_->queryRange(wholeOf(scene, 1));
    const QueryIndex each = backend_->queryTriangles(wholeOf(scene, 1));
    const QueryIndex listed = backend_->queryTriangles(1, all);
    std::vector<std::uint8_t> answers;
    backend_->fetchResults(answers);
    ASSERT_EQ(answers.size(), 2 * n + 1);
    EXPECT_EQ(answers[whole], written ? 0 : 1);
    int visible = 0;
    for (std::size_t t = 0; t < n; ++t) {
      EXPECT_EQ(answers[each + t], answers[listed + t]) << "triangle " << t;
      visible += answers[each + t];
    }
    // With nothing written every triangle is visible. Behind A every one is occluded in
    // conservative mode (raw mode answers visible for those that cover no pixel centre).
    if (!written) {
      EXPECT_EQ(visible, static_cast<int>(n));
    }
    if (written && conservative) {
      EXPECT_EQ(visible, 0) << "behind A";
    }
    if (written) {
      EXPECT_LT(visible, static_cast<int>(n) / 2) << "behind A";
    }
  }
}

// A closed mesh whose parts wind different ways (a box wound outward beside one wound inward, which
// straddles a small wall): drawn whole, it answers as if every triangle were drawn. Which faces
// decide such a mesh cannot be told from its winding as a whole (positive here): in the inward box
// the faces wound as turned away from the viewer are the nearest, so a backend drawing only those
// for a test would miss its far side behind the wall, and one drawing only the faces wound as
// turned toward the viewer for a write would store the far side, behind the wall.
TEST_P(OcclusionSemantics, AClosedMeshWoundBothWaysAnswersAsEveryTriangleDrawn) {
  for (bool inward : {true, false}) {
    const Mesh parts = test::boxesWoundBothWays(inward);
    const SceneGeometry scene = test::sceneOf({squareMesh(0, 0, 0, 0.3f), parts});
    backend_->attachScene(scene);
    backend_->setPoses(test::identityPoses(scene.objectCount()));
    backend_->beginPass(view(Eigen::Vector3d::UnitZ(), 128), DepthUse::Fresh);
    backend_->writeRange(wholeOf(scene, 0));
    backend_->queryRange(wholeOf(scene, 1));
    backend_->beginPass(view(Eigen::Vector3d::UnitZ(), 128), DepthUse::Fresh);
    backend_->writeRange(wholeOf(scene, 1));
    backend_->queryRange(wholeOf(scene, 0));
    std::vector<std::uint8_t> answers;
    backend_->fetchResults(answers);
    const char* which = inward ? "the small box wound inward" : "both boxes wound outward";
    ASSERT_EQ(answers.size(), 2u);
    EXPECT_EQ(answers[0], 0) << which << ": its far side lies behind the wall";
    EXPECT_EQ(answers[1], 0) << which << ": its near side lies in front of the wall";
  }
}

// A node's test and write draw the same boxes, and CULLIDE's two passes of a view draw them
// again (the cpu backend records such repeats once): boxes drawn again answer for where they are
// drawn now, under another pose, in another view, or with other contents in the same array.
TEST_P(OcclusionSemantics, BoxesDrawnAgainAnswerWhereTheyAreNow) {
  std::vector<OrientedBox> boxes(1);  // of object 3, at the identity pose
  boxes[0].halfExtents = Eigen::Vector3d(0.5, 0.5, 0.1);
  boxes[0].center = Eigen::Vector3d(0, 0, -2.5);  // in front of C (z = -2), so of A

  backend_->beginPass(view(Eigen::Vector3d::UnitZ()), DepthUse::Fresh);
  backend_->writeRange(wholeOf(scene_, 0));
  const QueryIndex inFront = backend_->queryBoxes(3, boxes);
  backend_->writeBoxes(3, boxes);
  const QueryIndex cBehindTheBox = backend_->queryRange(wholeOf(scene_, 2));
  std::vector<Pose> moved = test::identityPoses(scene_.objectCount());
  moved[3].translation = Eigen::Vector3d(0, 0, 5);  // the box at z = 2.5, behind A
  backend_->setPoses(moved);
  backend_->beginPass(view(Eigen::Vector3d::UnitZ()), DepthUse::Fresh);
  backend_->writeRange(wholeOf(scene_, 0));
  const QueryIndex movedBehind = backend_->queryBoxes(3, boxes);
  backend_->setPoses(test::identityPoses(scene_.objectCount()));
  backend_->beginPass(view(Eigen::Vector3d::UnitZ()), DepthUse::Fresh);
  backend_->writeRange(wholeOf(scene_, 0));
  const QueryIndex again = backend_->queryBoxes(3, boxes);
  boxes[0].center.z() = 2.5;  // the same array, now behind A
  const QueryIndex changed = backend_->queryBoxes(3, boxes);
  backend_->beginPass(view(-Eigen::Vector3d::UnitZ()), DepthUse::Fresh);
  backend_->writeRange(wholeOf(scene_, 0));
  const QueryIndex otherView = backend_->queryBoxes(3, boxes);
  std::vector<std::uint8_t> answers;
  backend_->fetchResults(answers);
  ASSERT_EQ(answers.size(), 6u);
  EXPECT_EQ(answers[inFront], 1) << "the box in front of A";
  EXPECT_EQ(answers[cBehindTheBox], 0) << "C behind the box written with the boxes just tested";
  EXPECT_EQ(answers[movedBehind], 0) << "the same boxes, their object moved behind A";
  EXPECT_EQ(answers[again], 1) << "back in front of A";
  EXPECT_EQ(answers[changed], 0) << "the array's box moved behind A";
  EXPECT_EQ(answers[otherView], 1) << "in front of A looking along -z";
}

// `copies` squares of half size h centred on (cx, cy), the first at z, each next dz farther, as
// one mesh.
Mesh squareStack(int copies, float cx, float cy, float z, float h, float dz);

// A batch test and the write of its triangles draw the same list, and CULLIDE's two passes of a
// view draw it again (the cpu backend records such repeats once, and bounds them once): listed
// triangles drawn again answer for where they are drawn now, under another pose, in another view,
// and in the order they are listed.
TEST_P(OcclusionSemantics, ListedTrianglesDrawnAgainAnswerWhereTheyAreNow) {
  // Object 5: two squares over A, triangles 0 and 1 in front of it (z = -2), 2 and 3 behind it
  // (z = 2).
  scene_ = test::sceneOf({squareMesh(0, 0, 0, 1), squareMesh(0, 0, 2, 1), squareMesh(0, 0, -2, 1),
                          squareMesh(5, 0, 0, 1), squareMesh(0.5f, 0, 0, 1),
                          squareStack(2, 0, 0, -2, 1, 4)});
  backend_->attachScene(scene_);
  backend_->setPoses(test::identityPoses(scene_.objectCount()));
  const std::vector<std::uint32_t> frontThenBack = {0, 2};
  const std::vector<std::uint32_t> front = {0, 1};
  const auto pass = [&](const Eigen::Vector3d& direction) {
    backend_->beginPass(view(direction), DepthUse::Fresh);
    backend_->writeRange(wholeOf(scene_, 0));
  };
  pass(Eigen::Vector3d::UnitZ());
  const QueryIndex first = backend_->queryTriangles(5, frontThenBack);
  backend_->writeTriangles(5, frontThenBack);
  pass(Eigen::Vector3d::UnitZ());  // the same view: the same list under the same matrix
  const QueryIndex again = backend_->queryTriangles(5, frontThenBack);
  backend_->writeTriangles(5, frontThenBack);
  pass(Eigen::Vector3d::UnitZ());
  const QueryIndex frontSquare = backend_->queryTriangles(5, front);
  std::vector<Pose> moved = test::identityPoses(scene_.objectCount());
  moved[5].translation = Eigen::Vector3d(0, 0, 10);  // both squares behind A
  backend_->setPoses(moved);
  pass(Eigen::Vector3d::UnitZ());
  const QueryIndex frontMoved = backend_->queryTriangles(5, front);
  const QueryIndex movedBehind = backend_->queryTriangles(5, frontThenBack);
  backend_->setPoses(test::identityPoses(scene_.objectCount()));
  pass(-Eigen::Vector3d::UnitZ());
  const QueryIndex otherView = backend_->queryTriangles(5, frontThenBack);
  pass(Eigen::Vector3d::UnitZ());
  const QueryIndex reversed = backend_->queryTriangles(5, std::vector<std::uint32_t>{2, 0});
  std::vector<std::uint8_t> answers;
  backend_->fetchResults(answers);
  ASSERT_EQ(answers.size(), 14u);
  EXPECT_EQ(answers[first], 1) << "a triangle in front of A";
  EXPECT_EQ(answers[first + 1], 0) << "a triangle behind A";
  EXPECT_EQ(answers[frontSquare], 1) << "the front square, in front of A";
  EXPECT_EQ(answers[frontSquare + 1], 1) << "the front square's other triangle";
  EXPECT_EQ(answers[again], 1) << "the same list again, in front";
  EXPECT_EQ(answers[again + 1], 0) << "the same list again, behind";
  EXPECT_EQ(answers[movedBehind], 0) << "the front triangle, its object moved behind A";
  EXPECT_EQ(answers[movedBehind + 1], 0) << "the back triangle, moved farther";
  EXPECT_EQ(answers[frontMoved], 0) << "the front square moved behind A";
  EXPECT_EQ(answers[frontMoved + 1], 0) << "the front square moved behind A";
  EXPECT_EQ(answers[otherView], 0) << "looking along -z the front triangle is behind A";
  EXPECT_EQ(answers[otherView + 1], 1) << "and the back one in front";
  EXPECT_EQ(answers[reversed], 0) << "listed first now: the triangle behind A";
  EXPECT_EQ(answers[reversed + 1], 1) << "listed second: the one in front";
}

// CULLIDE's two passes of a view draw each whole mesh again in the same role under the same
// matrix (the cpu backend bounds such repeats once): a mesh drawn again answers for where it is
// drawn now.
TEST_P(OcclusionSemantics, MeshesDrawnAgainAnswerWhereTheyAreNow) {
  const auto pass = [&] {
    backend_->beginPass(view(Eigen::Vector3d::UnitZ()), DepthUse::Fresh);
    backend_->writeRange(wholeOf(scene_, 0));
  };
  pass();
  const QueryIndex inFront = backend_->queryRange(wholeOf(scene_, 2));
  backend_->writeRange(wholeOf(scene_, 2));
  pass();
  const QueryIndex again = backend_->queryRange(wholeOf(scene_, 2));
  backend_->writeRange(wholeOf(scene_, 2));
  std::vector<Pose> moved = test::identityPoses(scene_.objectCount());
  moved[2].translation = Eigen::Vector3d(0, 0, 4);  // C at z = 2, behind A
  backend_->setPoses(moved);
  pass();
  const QueryIndex movedBehind = backend_->queryRange(wholeOf(scene_, 2));
  std::vector<std::uint8_t> answers;
  backend_->fetchResults(answers);
  ASSERT_EQ(answers.size(), 3u);
  EXPECT_EQ(answers[inFront], 1) << "C in front of A";
  EXPECT_EQ(answers[again], 1) << "C in front of A, in the same view again";
  EXPECT_EQ(answers[movedBehind], 0) << "C moved behind A";
}

Mesh squareStack(int copies, float cx, float cy, float z, float h, float dz) {
  Mesh stack;
  stack.name = "square stack";
  for (int copy = 0; copy < copies; ++copy) {
    const Mesh square = squareMesh(cx, cy, z + dz * static_cast<float>(copy), h);
    const auto first = static_cast<std::uint32_t>(stack.vertices.size());
    stack.vertices.insert(stack.vertices.end(), square.vertices.begin(), square.vertices.end());
    for (const Triangle& t : square.triangles)
      stack.triangles.push_back({first + t[0], first + t[1], first + t[2]});
  }
  return stack;
}

// Thousands of draws over the same pixels in one pass keep their issue order: tests issued before
// a write do not see it, tests after it do. The tested object is 64 copies of B's square, so that
// each of its draws reaches every pixel 128 times: over 300,000 piece evaluations a pixel.
// (gl-compute lists each draw's chunks of 64 pieces in every tile they reach and sorts the lists
// back into issue order: lists this long are sorted in global memory; llvmpipe ends a shader
// invocation's loops after 65,535 iterations, so there the tiles are evaluated in several
// dispatches.)
TEST_P(OcclusionSemantics, ThousandsOfDrawsOverOnePixelKeepTheirOrder) {
  const Mesh stack = squareStack(64, 0, 0, 2, 1, 0);
  scene_ = test::sceneOf(
      {squareMesh(0, 0, 0, 1), stack, squareMesh(0, 0, -2, 1), squareMesh(5, 0, 0, 1)});
  backend_->attachScene(scene_);
  backend_->setPoses(test::identityPoses(scene_.objectCount()));
  constexpr int kBefore = 1200, kAfter = 1200;
  backend_->beginPass(view(Eigen::Vector3d::UnitZ()), DepthUse::Fresh);
  std::vector<QueryIndex> before, after, inFront;
  for (int i = 0; i < kBefore; ++i) before.push_back(backend_->queryRange(wholeOf(scene_, 1)));
  backend_->writeRange(wholeOf(scene_, 0));  // A, in front of the stack
  for (int i = 0; i < kAfter; ++i) {
    after.push_back(backend_->queryRange(wholeOf(scene_, 1)));
    if (i % 100 == 0) inFront.push_back(backend_->queryRange(wholeOf(scene_, 2)));
  }
  std::vector<std::uint8_t> answers;
  backend_->fetchResults(answers);
  ASSERT_EQ(answers.size(), before.size() + after.size() + inFront.size());
  int seenBefore = 0, missedAfter = 0, hiddenInFront = 0;
  for (QueryIndex q : before) seenBefore += answers[q] == 0;
  for (QueryIndex q : after) missedAfter += answers[q] == 1;
  for (QueryIndex q : inFront) hiddenInFront += answers[q] == 0;
  EXPECT_EQ(seenBefore, 0) << "the stack tested before A was written is fully visible";
  EXPECT_EQ(missedAfter, 0) << "the stack tested after A was written is behind it";
  EXPECT_EQ(hiddenInFront, 0) << "C in front of A stays fully visible";
}

// A write of many large triangles covering the whole image at 800 px hides what lies behind it in
// every corner. (gl-compute bins each chunk of 64 pieces to the 2,500 tiles it reaches: a loop
// llvmpipe would have cut short had one invocation walked them all.)
TEST_P(OcclusionSemantics, AWriteCoveringTheImageHidesEveryCorner) {
  const Mesh wall = squareStack(64, 2.5f, 0, 0, 20, 0.01f);
  scene_ = test::sceneOf({wall, squareMesh(-1.6f, -1.6f, 2, 0.3f), squareMesh(6.6f, 1.6f, 2, 0.3f),
                          squareMesh(-1.6f, 1.6f, 2, 0.3f), squareMesh(6.6f, -1.6f, 2, 0.3f),
                          squareMesh(2.5f, 0, -2, 0.3f)});
  backend_->attachScene(scene_);
  backend_->setPoses(test::identityPoses(scene_.objectCount()));
  backend_->beginPass(view(Eigen::Vector3d::UnitZ(), 800), DepthUse::Fresh);
  backend_->writeRange(wholeOf(scene_, 0));
  for (ObjectId corner = 1; corner <= 5; ++corner) backend_->queryRange(wholeOf(scene_, corner));
  std::vector<std::uint8_t> answers;
  backend_->fetchResults(answers);
  EXPECT_EQ(answers, (std::vector<std::uint8_t>{0, 0, 0, 0, 1}))
      << "four corners behind the wall, one square in front of it";
}

INSTANTIATE_TEST_SUITE_P(Backends, OcclusionSemantics,
                         testing::Combine(testing::ValuesIn(test::registeredBackends()),
                                          testing::Bool()),
                         ParamName());

}  // namespace
}  // namespace cdb
