// The cpu backend's demand-driven, tile-parallel evaluation against its plain evaluation (one tile
// the whole frame, every write rasterised where it is drawn, every test tested, no early-out):
// the same answers and the same stored depths, whatever the tile size and the thread count, on
// CULLIDE-like draws, on pieces decided by bounds, and on random scenes and command streams
// (tests, writes, batches, boxes, both depth uses, fetches in the middle of a pass).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <numbers>
#include <random>
#include <span>
#include <vector>

#include "core/Errors.h"
#include "culling/visibility/cpu/CpuRasterBackend.h"
#include "tests/common/SphereMeshes.h"
#include "tests/visibility/GlTestSupport.h"

// Helpers in a namespace of their own: unity builds compile test files together.
namespace cdb::demand_evaluation_test {
namespace {

// A closed sphere of `rings` x `segments` quads (two triangles each, caps of triangles), wound
// counter-clockwise seen from outside, its vertices moved radially at random so that it is not
// convex: many small triangles that overlap in depth.
Mesh bumpySphere(unsigned seed, int rings, int segments) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> bump(0.7f, 1.0f);
  Mesh m = test::ringSphere(rings, segments, [&](double theta, double phi) -> Eigen::Vector3f {
    if (theta == 0.0) return {0.f, 0.f, bump(rng)};                // north pole
    if (theta == std::numbers::pi) return {0.f, 0.f, -bump(rng)};  // south pole
    const float radius = bump(rng);
    return Eigen::Vector3f(radius * std::sin(theta) * std::cos(phi),
                           radius * std::sin(theta) * std::sin(phi), radius * std::cos(theta));
  });
  m.name = "bumpy sphere";
  return m;
}

std::vector<Pose> posesAround(unsigned seed, std::size_t n, double spread) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Pose> poses(n);
  for (Pose& p : poses) {
    p.rotation = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized();
    p.translation = Eigen::Vector3d(u(rng), u(rng), u(rng)) * spread;
  }
  return poses;
}

// What a command stream gave: the answers of every fetch, the buffer the last pass left, and the
// counters of what was issued (those of work done differ by design).
struct Outcome {
  std::vector<std::vector<std::uint8_t>> answers;
  std::vector<float> buffer;
  VisibilityCounters counters;
};

using Stream = std::function<void(CpuRasterBackend&, Outcome&)>;

Outcome run(const SceneGeometry& scene, const std::vector<Pose>& poses, const Stream& stream,
            bool conservative, const CpuEvaluation& evaluation, int threads) {
  CpuRasterBackend backend(VisibilityOptions{conservative, 1e-5, threads});
  backend.setEvaluation(evaluation);
  backend.attachScene(scene);
  backend.setPoses(poses);
  Outcome out;
  stream(backend, out);
  out.counters = backend.counters();
  return out;
}

void fetchInto(CpuRasterBackend& backend, Outcome& out) {
  std::vector<std::uint8_t> answers;
  backend.fetchResults(answers);
  out.answers.push_back(answers);
}

void readBuffer(CpuRasterBackend& backend, int resolution, Outcome& out) {
  for (int y = 0; y < resolution; ++y)
    for (int x = 0; x < resolution; ++x) out.buffer.push_back(backend.storedDepth(x, y));
}

constexpr CpuEvaluation kPlain{0, false, false};

// The demand-driven settings compared with the plain evaluation, one test case each: tiles of one
// block, of 4 x 4 and of 8 x 8, with and without the early-out, with the default limits on pending
// writes or with so few allowed (2 a block, 7 a tile) that they are drawn all the time; each at
// 1, 2 and 4 threads.
using Setting = std::tuple<int, bool, bool>;

class CpuDemandEvaluation : public testing::TestWithParam<Setting> {
 public:
  // Compares the case's setting at 1, 2 and 4 threads with the plain evaluation; returns the plain
  // outcome.
  Outcome expectSameAsPlain(const SceneGeometry& scene, const std::vector<Pose>& poses,
                            const Stream& stream, bool conservative) const {
    const auto [tile, earlyOut, fewPending] = GetParam();
    CpuEvaluation evaluation{tile, true, earlyOut};
    if (fewPending) evaluation.mostPendingInBlock = 2, evaluation.mostPendingInTile = 7;
    const Outcome plain = run(scene, poses, stream, conservative, kPlain, 1);
    for (int threads : {1, 2, 4}) {
      SCOPED_TRACE(testing::Message() << threads << " threads");
      const Outcome demand = run(scene, poses, stream, conservative, evaluation, threads);
      EXPECT_EQ(demand.answers, plain.answers);
      EXPECT_EQ(demand.buffer, plain.buffer);
      EXPECT_EQ(demand.counters.queries, plain.counters.queries);
      EXPECT_EQ(demand.counters.draws, plain.counters.draws);
      EXPECT_EQ(demand.counters.trianglesDrawn, plain.counters.trianglesDrawn);
      EXPECT_EQ(demand.counters.fetches, plain.counters.fetches);
      // The point of it: fewer pixels written than drawing every write.
      EXPECT_LE(demand.counters.pixelsWritten, plain.counters.pixelsWritten);
    }
    return plain;
  }
};

INSTANTIATE_TEST_SUITE_P(Settings, CpuDemandEvaluation,
                         testing::Combine(testing::Values(8, 32, 64), testing::Bool(),
                                          testing::Bool()),
                         [](const auto& param) {
                           return "tile" + std::to_string(std::get<0>(param.param)) +
                                  (std::get<1>(param.param) ? "_earlyout" : "_noearlyout") +
                                  (std::get<2>(param.param) ? "_fewpending" : "");
                         });

// Both answers occur, and the buffer holds more than its clear value: the comparison decides
// something.
void expectBothAnswers(const Outcome& outcome) {
  int visible = 0, total = 0;
  for (const auto& fetch : outcome.answers)
    for (std::uint8_t v : fetch) visible += v, ++total;
  EXPECT_GT(visible, total / 20);
  EXPECT_LT(visible, total - total / 20);
  if (!outcome.buffer.empty()) {
    EXPECT_NE(std::ranges::min(outcome.buffer), std::ranges::max(outcome.buffer));
  }
}

// Nine bumpy spheres of 18-20 rings (the scene of CULLIDE's draws below).
SceneGeometry bumpySpheres() {
  std::vector<Mesh> meshes;
  for (int o = 0; o < 9; ++o) meshes.push_back(bumpySphere(11 + o, 18 + o % 3, 16));
  return test::sceneOf(std::move(meshes));
}

// Thirty boxes in a slanted row across an object, overlapping: its hierarchy nodes, as drawn.
std::vector<OrientedBox> nodeBoxes() {
  std::vector<OrientedBox> boxes(30);
  for (std::size_t b = 0; b < boxes.size(); ++b) {
    boxes[b].center = Eigen::Vector3d(0.05 * b - 0.7, -0.2 + 0.01 * b, 0.01 * b);
    boxes[b].halfExtents = Eigen::Vector3d(0.08, 0.05 + 0.004 * b, 0.06);
  }
  return boxes;
}

// CULLIDE's draws along each axis (pass 1 tests and writes every object in order, pass 2 in
// reverse, fresh depth, one fetch), then a triangle level (per member a batch of tests, then its
// listed triangles written), a pair of depth-sorted passes (one clear, opposite views) and node
// boxes tested and written in both passes of a view, then in a pair of depth-sorted passes. With
// `gated`, each pass-2 test of CULLIDE's passes and of the boxes is gated by the same piece's
// pass-1 test, as the strategies gate them (VisibilityBackend::gateAnswers).
Stream cullideDraws(const SceneGeometry& scene, int resolution, bool gated = true) {
  return [&scene, resolution, gated](CpuRasterBackend& backend, Outcome& out) {
    const Aabb bounds(Eigen::Vector3d::Constant(-2.5), Eigen::Vector3d::Constant(2.5));
    const auto objects = static_cast<ObjectId>(scene.objectCount());
    std::vector<QueryIndex> firstPass(objects);
    // Object o's test in pass `pass` (issued as `q`), gated in pass 2 by its pass-1 test.
    const auto gate = [&](int pass, ObjectId o, QueryIndex q, std::size_t count) {
      if (pass == 0) firstPass[o] = q;
      if (pass == 1 && gated)
        backend.gateAnswers(q, firstPass[o], static_cast<std::uint32_t>(count));
    };
    for (int axis = 0; axis < 3; ++axis) {
      const ViewSpec view{Eigen::Vector3d::Unit(axis), bounds, resolution};
      for (int pass = 0; pass < 2; ++pass) {
        backend.beginPass(view, DepthUse::Fresh);
        for (ObjectId i = 0; i < objects; ++i) {
          const ObjectId o = pass == 0 ? i : objects - 1 - i;
          gate(pass, o, backend.queryRange(test::wholeOf(scene, o)), 1);
          backend.writeRange(test::wholeOf(scene, o));
        }
      }
      fetchInto(backend, out);
    }
    std::vector<std::vector<std::uint32_t>> lists(objects);
    for (ObjectId o = 0; o < objects; ++o)
      for (std::uint32_t t = 0; t < scene.meshOf(o).triangleCount(); ++t)
        if ((t + o) % 5 != 0) lists[o].push_back(t);
    const ViewSpec side{Eigen::Vector3d(1, 1, 0).normalized(), bounds, resolution};
    for (int pass = 0; pass < 2; ++pass) {
      backend.beginPass(side, DepthUse::Fresh);
      for (ObjectId i = 0; i < objects; ++i) {
        const ObjectId o = pass == 0 ? i : objects - 1 - i;
        gate(pass, o, backend.queryTriangles(o, lists[o]), lists[o].size());
        backend.writeTriangles(o, lists[o]);
      }
    }
    fetchInto(backend, out);
    const ViewSpec up{Eigen::Vector3d::UnitZ(), bounds, resolution};
    ViewSpec down = up;
    down.direction = -up.direction;
    backend.beginPass(up, DepthUse::SharedFirst);
    for (ObjectId o = 0; o < objects; ++o) {
      backend.queryRange(test::wholeOf(scene, o));
      backend.writeRange(test::wholeOf(scene, o));
    }
    backend.beginPass(down, DepthUse::SharedSecond);
    for (ObjectId o = objects; o-- > 0;) {
      backend.queryRange(test::wholeOf(scene, o));
      backend.writeRange(test::wholeOf(scene, o));
    }
    fetchInto(backend, out);
    const std::vector<OrientedBox> boxes = nodeBoxes();
    for (int pass = 0; pass < 2; ++pass) {
      backend.beginPass(up, DepthUse::Fresh);
      for (ObjectId i = 0; i < objects; ++i) {
        const ObjectId o = pass == 0 ? i : objects - 1 - i;
        gate(pass, o, backend.queryBoxes(o, boxes), boxes.size());
        backend.writeBoxes(o, boxes);
      }
    }
    fetchInto(backend, out);
    // The same boxes in a pair of depth-sorted passes, as `ours` draws its nodes: recorded again
    // under the opposite view, pass 2's tests gated by pass 1's.
    for (int pass = 0; pass < 2; ++pass) {
      backend.beginPass(pass == 0 ? up : down,
                        pass == 0 ? DepthUse::SharedFirst : DepthUse::SharedSecond);
      for (ObjectId i = 0; i < objects; ++i) {
        const ObjectId o = pass == 0 ? i : objects - 1 - i;
        gate(pass, o, backend.queryBoxes(o, boxes), boxes.size());
        backend.writeBoxes(o, boxes);
      }
    }
    fetchInto(backend, out);
    readBuffer(backend, resolution, out);
  };
}

TEST_P(CpuDemandEvaluation, CullideDrawsAnswerAsPlainEvaluation) {
  const SceneGeometry scene = bumpySpheres();
  const std::vector<Pose> poses = posesAround(3, scene.objectCount(), 1.2);
  for (bool conservative : {true, false})
    for (int resolution : {64, 201}) {
      SCOPED_TRACE(testing::Message()
                   << (conservative ? "conservative" : "raw") << " at " << resolution << " px");
      expectBothAnswers(
          expectSameAsPlain(scene, poses, cullideDraws(scene, resolution), conservative));
    }
}

// Gating pass 2 by pass 1 changes no answer CULLIDE reads (the parametrised cases above compare
// gated streams with the plain evaluation, which tests every piece) and is what skips work: with
// the early-out, the gated stream tests fewer pieces and pixels than the same stream ungated, and
// its pass-2 answers are the ungated ones ANDed with pass 1's.
TEST(CpuGatedTests, PassTwoSkipsWhatPassOneFoundOccluded) {
  const SceneGeometry scene = bumpySpheres();
  const std::vector<Pose> poses = posesAround(3, scene.objectCount(), 1.2);
  const CpuEvaluation demand{};
  for (int threads : {1, 2}) {
    SCOPED_TRACE(testing::Message() << threads << " threads");
    const Outcome gated = run(scene, poses, cullideDraws(scene, 96, true), true, demand, threads);
    const Outcome ungated =
        run(scene, poses, cullideDraws(scene, 96, false), true, demand, threads);
    ASSERT_EQ(gated.answers.size(), ungated.answers.size());
    EXPECT_EQ(gated.buffer, ungated.buffer);
    // The first fetches hold an axis each: pass 1's answers, then pass 2's in reverse order.
    const std::size_t n = scene.objectCount();
    int gatedOff = 0;
    for (std::size_t axis = 0; axis < 3; ++axis) {
      const auto& g = gated.answers[axis];
      const auto& u = ungated.answers[axis];
      ASSERT_EQ(g.size(), 2 * n);
      for (std::size_t i = 0; i < n; ++i) {
        EXPECT_EQ(g[i], u[i]) << "pass 1, object " << i;
        const std::size_t second = 2 * n - 1 - i;
        EXPECT_EQ(g[second], u[second] && u[i]) << "pass 2, object " << i;
        gatedOff += u[second] && !u[i];
      }
    }
    EXPECT_GT(gatedOff, 0) << "no object visible in pass 2 only: nothing to skip";
    EXPECT_GT(gated.counters.tileTestsSkipped, ungated.counters.tileTestsSkipped);
    EXPECT_LT(gated.counters.pixelsTested, ungated.counters.pixelsTested);
  }
}

// The gate holds between the same boxes recorded twice, under views looking opposite ways (the
// passes of depth-sorted culling: `ours` gates its nodes' pass-2 tests so): the gated stream
// skips tests the ungated one makes, and its pass-2 answers are the ungated ones ANDed with
// pass 1's.
TEST(CpuGatedTests, BoxesOfTheOppositeViewKeepTheirGate) {
  const SceneGeometry scene = bumpySpheres();
  const std::vector<Pose> poses = posesAround(3, scene.objectCount(), 1.2);
  const std::vector<OrientedBox> boxes = nodeBoxes();
  const auto draws = [&](bool gated) -> Stream {
    return [&, gated](CpuRasterBackend& backend, Outcome& out) {
      const Aabb bounds(Eigen::Vector3d::Constant(-2.5), Eigen::Vector3d::Constant(2.5));
      const auto objects = static_cast<ObjectId>(scene.objectCount());
      for (int axis = 0; axis < 3; ++axis) {
        const ViewSpec view{Eigen::Vector3d::Unit(axis), bounds, 96};
        ViewSpec opposite = view;
        opposite.direction = -view.direction;
        std::vector<QueryIndex> first(objects);
        backend.beginPass(view, DepthUse::SharedFirst);
        for (ObjectId o = 0; o < objects; ++o) {
          first[o] = backend.queryBoxes(o, boxes);
          backend.writeBoxes(o, boxes);
        }
        backend.beginPass(opposite, DepthUse::SharedSecond);
        for (ObjectId o = objects; o-- > 0;) {
          const QueryIndex q = backend.queryBoxes(o, boxes);
          if (gated) backend.gateAnswers(q, first[o], static_cast<std::uint32_t>(boxes.size()));
          backend.writeBoxes(o, boxes);
        }
        fetchInto(backend, out);
      }
    };
  };
  for (int threads : {1, 2}) {
    SCOPED_TRACE(testing::Message() << threads << " threads");
    const Outcome gated = run(scene, poses, draws(true), true, CpuEvaluation{}, threads);
    const Outcome ungated = run(scene, poses, draws(false), true, CpuEvaluation{}, threads);
    const std::size_t n = scene.objectCount() * boxes.size();
    int gatedOff = 0;
    for (std::size_t axis = 0; axis < 3; ++axis) {
      const auto& g = gated.answers[axis];
      const auto& u = ungated.answers[axis];
      ASSERT_EQ(g.size(), 2 * n);
      // Pass 2 asks the objects in reverse order, each object's boxes in their own order.
      for (std::size_t o = 0; o < scene.objectCount(); ++o)
        for (std::size_t b = 0; b < boxes.size(); ++b) {
          const std::size_t one = o * boxes.size() + b;
          const std::size_t two = n + (scene.objectCount() - 1 - o) * boxes.size() + b;
          EXPECT_EQ(g[one], u[one]) << "pass 1, object " << o << ", box " << b;
          EXPECT_EQ(g[two], u[two] && u[one]) << "pass 2, object " << o << ", box " << b;
          gatedOff += u[two] && !u[one];
        }
    }
    EXPECT_GT(gatedOff, 0) << "no box visible in pass 2 only: nothing to skip";
    EXPECT_GT(gated.counters.tileTestsSkipped, ungated.counters.tileTestsSkipped);
  }
}

// One command's writes walked with no test between them are pending as one group (CpuPendingGroup)
// in their blocks' lists; a test that can see some of them has only those drawn. Ten boxes of one
// object written one behind the other over the same pixels, then a thin box of another object
// tested between the fifth and the sixth: it is occluded (the five in front drawn), and only those
// five of the ten writes are drawn, as with the plain evaluation's answers.
TEST(CpuPendingGroups, ATestDrawsOnlyTheWritesOfAGroupThatCanLieInFrontOfIt) {
  const SceneGeometry scene = bumpySpheres();
  const std::vector<Pose> poses(scene.objectCount());  // identities
  std::vector<OrientedBox> layers(10);
  for (std::size_t b = 0; b < layers.size(); ++b) {
    layers[b].center = Eigen::Vector3d(0.0, 0.0, -0.9 + 0.2 * static_cast<double>(b));
    layers[b].halfExtents = Eigen::Vector3d(0.6, 0.6, 0.02);
  }
  OrientedBox between;
  between.center = Eigen::Vector3d(0.0, 0.0, 0.0);
  between.halfExtents = Eigen::Vector3d(0.2, 0.2, 0.02);
  const Stream stream = [&](CpuRasterBackend& backend, Outcome& out) {
    const Aabb bounds(Eigen::Vector3d::Constant(-1.0), Eigen::Vector3d::Constant(1.0));
    for (const double direction : {1.0, -1.0}) {
      backend.beginPass(ViewSpec{Eigen::Vector3d(0.0, 0.0, direction), bounds, 64},
                        DepthUse::Fresh);
      backend.writeBoxes(0, layers);
      (void)backend.queryBoxes(1, {&between, 1});
      fetchInto(backend, out);
    }
  };
  const Outcome plain = run(scene, poses, stream, true, kPlain, 1);
  for (const int threads : {1, 2}) {
    SCOPED_TRACE(testing::Message() << threads << " threads");
    const Outcome demand = run(scene, poses, stream, true, CpuEvaluation{}, threads);
    EXPECT_EQ(demand.answers, plain.answers);
    ASSERT_EQ(demand.answers.size(), 2u);
    for (const auto& answers : demand.answers) EXPECT_EQ(answers, std::vector<std::uint8_t>{0});
    // One tile (64 px), both views: five writes in front each time.
    EXPECT_EQ(demand.counters.tileWrites, 20u);
    EXPECT_EQ(demand.counters.tileWritesRasterised, 10u);
  }
}

// A wall (a square facing the view) written first, then small spheres scattered over and around
// it, some in front, some behind, some through it, each tested and written, then each tested
// again: many tests decided by bounds, and many pieces whose bounds end near a tile's edge.
TEST_P(CpuDemandEvaluation, PiecesDecidedByBoundsAnswerAsPlainEvaluation) {
  for (unsigned seed : {1u, 2u}) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<Mesh> meshes{test::squareMesh(0.f, 0.f, 0.f, 1.f)};
    std::vector<Pose> poses(1);
    for (int o = 0; o < 40; ++o) {
      Mesh m = bumpySphere(seed + o, 6, 8);
      for (auto& v : m.vertices) v *= 0.12f;
      meshes.push_back(std::move(m));
      Pose p;
      p.translation = Eigen::Vector3d(1.3 * u(rng), 1.3 * u(rng), 0.25 * u(rng));
      poses.push_back(p);
    }
    const SceneGeometry scene = test::sceneOf(std::move(meshes));
    for (bool conservative : {true, false})
      for (int resolution : {64, 100}) {
        SCOPED_TRACE(testing::Message() << (conservative ? "conservative" : "raw") << " at "
                                        << resolution << " px, seed " << seed);
        const Stream wall = [&scene, resolution](CpuRasterBackend& backend, Outcome& out) {
          const Aabb bounds(Eigen::Vector3d(-1.5, -1.5, -0.5), Eigen::Vector3d(1.5, 1.5, 0.5));
          const auto objects = static_cast<ObjectId>(scene.objectCount());
          backend.beginPass({Eigen::Vector3d::UnitZ(), bounds, resolution}, DepthUse::Fresh);
          backend.writeRange(test::wholeOf(scene, 0));
          for (ObjectId o = 1; o < objects; ++o) {
            backend.queryRange(test::wholeOf(scene, o));
            backend.writeRange(test::wholeOf(scene, o));
          }
          for (ObjectId o = 1; o < objects; ++o) backend.queryRange(test::wholeOf(scene, o));
          fetchInto(backend, out);
          readBuffer(backend, resolution, out);
        };
        expectBothAnswers(expectSameAsPlain(scene, poses, wall, conservative));
      }
  }
}

// Random scenes (small random meshes and bumpy spheres, touching and apart) and random command
// streams: every kind of draw, passes of either depth use at random resolutions, fetches at
// random points (between a SharedFirst pass and its SharedSecond, and in the middle of a pass,
// which then goes on).
SceneGeometry randomScene(std::mt19937& rng, int objects) {
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  std::vector<Mesh> meshes;
  for (int o = 0; o < objects; ++o) {
    if (o % 3 == 0) {
      Mesh m = bumpySphere(rng(), 5 + o % 4, 6 + o % 5);
      for (auto& v : m.vertices) v *= 0.4f;
      meshes.push_back(std::move(m));
      continue;
    }
    Mesh m;
    m.name = "random";
    const int triangles = 1 + static_cast<int>(rng() % 90);
    for (int t = 0; t < triangles; ++t) {
      const Eigen::Vector3f centre(u(rng), u(rng), u(rng));
      for (int v = 0; v < 3; ++v)
        m.vertices.push_back(centre * 0.4f + Eigen::Vector3f(u(rng), u(rng), u(rng)) * 0.15f);
      const auto first = static_cast<std::uint32_t>(3 * t);
      m.triangles.push_back({first, first + 1, first + 2});
    }
    meshes.push_back(std::move(m));
  }
  return test::sceneOf(std::move(meshes));
}

// Random draws of every kind in passes of every depth use but the order-independent one, with
// fetches between them; with `orderIndependent`, order-independent passes instead, each its writes
// then its tests (a test of an object reads no write of its own there).
Stream randomStream(unsigned seed, const SceneGeometry& scene, bool orderIndependent = false) {
  return [seed, &scene, orderIndependent](CpuRasterBackend& backend, Outcome& out) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const auto pick = [&](int n) { return static_cast<int>(rng() % static_cast<unsigned>(n)); };
    const auto objects = static_cast<ObjectId>(scene.objectCount());
    const int resolutions[] = {29, 64, 100, 157};
    int lastResolution = 64;
    const auto someTriangles = [&](ObjectId o) {
      std::vector<std::uint32_t> list;
      const auto count = static_cast<std::uint32_t>(scene.meshOf(o).triangleCount());
      for (std::uint32_t t = 0; t < count; ++t)
        if (pick(3) != 0) list.push_back(t);
      return list;
    };
    const auto someBoxes = [&] {
      std::vector<OrientedBox> boxes(1 + pick(5));
      for (OrientedBox& b : boxes) {
        b.center = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 0.4;
        b.axes = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
        b.halfExtents =
            Eigen::Vector3d(0.02 + 0.2 * std::abs(u(rng)), 0.02 + 0.2 * std::abs(u(rng)),
                            pick(6) == 0 ? 0.0 : 0.02 + 0.2 * std::abs(u(rng)));
      }
      return boxes;
    };
    // The tests issued since the last fetch (first answer, count); a third of them gated by an
    // earlier one of as many answers (most of the same object's pieces, as CULLIDE gates).
    std::vector<std::pair<QueryIndex, std::uint32_t>> issued;
    const auto maybeGate = [&](QueryIndex q, std::size_t count) {
      if (q == kNoQuery || count == 0) return;
      const auto n = static_cast<std::uint32_t>(count);
      std::vector<QueryIndex> gates;
      for (const auto& [first, c] : issued)
        if (c == n) gates.push_back(first);
      issued.emplace_back(q, n);
      if (!gates.empty() && pick(3) == 0)
        backend.gateAnswers(
            q, gates[static_cast<std::size_t>(pick(static_cast<int>(gates.size())))], n);
    };
    const auto fetch = [&] {
      fetchInto(backend, out);
      issued.clear();
    };
    // Draws of the kinds [kind0, kind0 + kinds) of the switch below.
    const auto drawsOf = [&](int count, int kind0, int kinds) {
      for (int d = 0; d < count; ++d) {
        const auto o = static_cast<ObjectId>(pick(static_cast<int>(objects)));
        const auto triangles = static_cast<std::uint32_t>(scene.meshOf(o).triangleCount());
        const std::uint32_t first = static_cast<std::uint32_t>(pick(static_cast<int>(triangles)));
        const MeshRange part{
            o, first, static_cast<std::uint32_t>(pick(static_cast<int>(triangles - first) + 1))};
        switch (kind0 + pick(kinds)) {
          case 0:
            maybeGate(backend.queryRange(test::wholeOf(scene, o)), 1);
            break;
          case 1:
            maybeGate(backend.queryRange(part), 1);
            break;
          case 2:
            maybeGate(backend.queryTriangles(part), part.triangleCount);
            break;
          case 3: {
            const std::vector<std::uint32_t> list = someTriangles(o);
            maybeGate(backend.queryTriangles(o, list), list.size());
            break;
          }
          case 4: {
            const std::vector<OrientedBox> boxes = someBoxes();
            maybeGate(backend.queryBoxes(o, boxes), boxes.size());
            break;
          }
          case 5:
            backend.writeRange(pick(2) ? test::wholeOf(scene, o) : part);
            break;
          case 6:
            backend.writeTriangles(o, someTriangles(o));
            break;
          case 7:
            backend.writeBoxes(o, someBoxes());
            break;
          default:  // a test and a write of the same object, as the strategies draw
            maybeGate(backend.queryRange(test::wholeOf(scene, o)), 1);
            backend.writeRange(test::wholeOf(scene, o));
        }
      }
    };
    const auto draws = [&](int count) { drawsOf(count, 0, 9); };
    for (int round = 0; round < 8; ++round) {
      if (orderIndependent) {
        const Eigen::Vector3d direction = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
        const double half = pick(2) ? 1.6 : 0.3 + 0.3 * std::abs(u(rng));
        const Aabb bounds(Eigen::Vector3d::Constant(-half), Eigen::Vector3d::Constant(half));
        lastResolution = resolutions[pick(4)];
        backend.beginPass({direction, bounds, lastResolution}, DepthUse::OrderIndependent);
        drawsOf(10 + pick(30), 5, 3);  // writes
        drawsOf(10 + pick(30), 0, 5);  // tests
        fetch();
        continue;
      }
      const Eigen::Vector3d direction = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
      const int resolution = resolutions[pick(4)];
      // Views holding every object, or a part (the rest off-screen, or clamped to the depth
      // range: pieces at equal keys).
      const double half = pick(2) ? 1.6 : 0.3 + 0.3 * std::abs(u(rng));
      const Aabb bounds(Eigen::Vector3d::Constant(-half), Eigen::Vector3d::Constant(half));
      if (pick(3) == 0) {
        // Two passes, one clear, opposite views; a fetch between them half of the time.
        backend.beginPass({direction, bounds, resolution}, DepthUse::SharedFirst);
        draws(10 + pick(20));
        if (pick(2)) fetch();
        backend.beginPass({-direction, bounds, resolution}, DepthUse::SharedSecond);
        draws(10 + pick(20));
      } else {
        backend.beginPass({direction, bounds, resolution}, DepthUse::Fresh);
        draws(10 + pick(30));
      }
      lastResolution = resolution;
      if (pick(3) != 0) fetch();
      if (pick(3) == 0) {  // the pass goes on after a fetch
        fetch();
        draws(5 + pick(10));
      }
    }
    fetch();
    readBuffer(backend, lastResolution, out);
  };
}

// Random streams (randomStream) of the seeds over random scenes, in both modes, as the plain
// evaluation answers them.
void expectRandomStreamsAsPlain(const CpuDemandEvaluation& test,
                                std::initializer_list<unsigned> seeds, bool orderIndependent) {
  for (unsigned seed : seeds) {
    std::mt19937 rng(seed * 7919u);
    const SceneGeometry scene = randomScene(rng, 24);
    const std::vector<Pose> poses = posesAround(seed, scene.objectCount(), 0.8);
    for (bool conservative : {true, false}) {
      SCOPED_TRACE(testing::Message()
                   << (conservative ? "conservative" : "raw") << ", seed " << seed);
      expectBothAnswers(test.expectSameAsPlain(
          scene, poses, randomStream(seed, scene, orderIndependent), conservative));
    }
  }
}

TEST_P(CpuDemandEvaluation, RandomOrderIndependentPassesAnswerAsPlainEvaluation) {
  expectRandomStreamsAsPlain(*this, {5u, 6u, 7u}, true);
}

TEST_P(CpuDemandEvaluation, RandomStreamsAnswerAsPlainEvaluation) {
  expectRandomStreamsAsPlain(*this, {1u, 2u, 3u, 4u}, false);
}

// Without the early-out a tile's work depends on nothing another tile does: the counters of work
// done do not depend on the thread count either.
TEST(CpuDemandWork, WithoutEarlyOutDoesNotDependOnThreads) {
  std::mt19937 rng(99);
  const SceneGeometry scene = randomScene(rng, 24);
  const std::vector<Pose> poses = posesAround(5, scene.objectCount(), 0.8);
  const CpuEvaluation evaluation{16, true, false};
  const Outcome one = run(scene, poses, randomStream(5, scene), true, evaluation, 1);
  const Outcome four = run(scene, poses, randomStream(5, scene), true, evaluation, 4);
  EXPECT_EQ(four.answers, one.answers);
  EXPECT_EQ(four.counters.pixelsWritten, one.counters.pixelsWritten);
  EXPECT_EQ(four.counters.pixelsTested, one.counters.pixelsTested);
  EXPECT_EQ(four.counters.tileTestsByBounds, one.counters.tileTestsByBounds);
  EXPECT_EQ(four.counters.tileWritesRasterised, one.counters.tileWritesRasterised);
  EXPECT_GT(one.counters.tileTestsByBounds, 0u);
  EXPECT_LT(one.counters.tileWritesRasterised, one.counters.tileWrites);
}

// Pieces beyond the depth range are clamped to its ends, so a write and a test there have equal
// keys, and equal is occluded: in front of the near plane in a fresh pass, behind the far plane of
// a SharedFirst pass (whose clear value lies beyond it). Their key bounds tie too.
TEST_P(CpuDemandEvaluation, TiesAtTheEndsOfTheDepthRange) {
  const SceneGeometry scene =
      test::sceneOf({test::squareMesh(0, 0, -5, 0.5f), test::squareMesh(0.2f, 0, -4, 0.5f),
                     test::squareMesh(0, 0, 5, 0.5f), test::squareMesh(0.2f, 0, 4, 0.5f)});
  const std::vector<Pose> poses(4);
  const Aabb bounds(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1));
  for (const DepthUse use : {DepthUse::Fresh, DepthUse::SharedFirst}) {
    const Stream ties = [&](CpuRasterBackend& backend, Outcome& out) {
      backend.beginPass({Eigen::Vector3d::UnitZ(), bounds, 64}, use);
      for (ObjectId o : {0u, 2u}) backend.writeRange(test::wholeOf(scene, o));
      for (ObjectId o : {1u, 3u}) backend.queryRange(test::wholeOf(scene, o));
      fetchInto(backend, out);
    };
    SCOPED_TRACE(use == DepthUse::Fresh ? "fresh" : "shared first");
    const Outcome plain = expectSameAsPlain(scene, poses, ties, true);
    ASSERT_EQ(plain.answers.size(), 1u);
    // Both tests tie with the write beside them (in a fresh pass the far one also with the clear
    // value, 1.0, the end of its range).
    EXPECT_EQ(plain.answers[0], (std::vector<std::uint8_t>{0, 0}));
  }
}

// Boxes of every shape: solid, flat (one half extent 0) and needles (two), turned at random or
// lying along the axes (so that views along an axis see flat ones edge-on), around the origin.
std::vector<OrientedBox> boxesOfEveryShape(std::mt19937& rng, int count) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<OrientedBox> boxes(static_cast<std::size_t>(count));
  for (std::size_t b = 0; b < boxes.size(); ++b) {
    OrientedBox& box = boxes[b];
    box.center = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 1.2;
    box.halfExtents =
        Eigen::Vector3d(0.3 + 0.25 * u(rng), 0.3 + 0.25 * u(rng), 0.3 + 0.25 * u(rng));
    if (b % 4 == 1) box.halfExtents[b % 3] = 0.0;
    if (b % 4 == 2) box.halfExtents[b % 3] = box.halfExtents[(b + 1) % 3] = 0.0;
    if (b % 2 == 0)
      box.axes = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
  }
  return boxes;
}

// Four objects' boxes of every shape, each object's tested then written, in views along the axes
// and askew, in fresh passes and in pairs of depth-sorted passes: box tests occluded from the
// depth stored under their centre (CpuTileEvaluation) among the others, flat boxes seen edge-on
// and writes still pending under a test's centre included.
TEST_P(CpuDemandEvaluation, BoxesOfEveryShapeAnswerAsPlainEvaluation) {
  const SceneGeometry scene = bumpySpheres();
  const std::vector<Pose> poses(scene.objectCount());
  std::mt19937 rng(7);
  std::vector<std::vector<OrientedBox>> boxes;
  for (int o = 0; o < 4; ++o) boxes.push_back(boxesOfEveryShape(rng, 12));
  const Stream draws = [&boxes](CpuRasterBackend& backend, Outcome& out) {
    const Aabb bounds(Eigen::Vector3d::Constant(-2.0), Eigen::Vector3d::Constant(2.0));
    const Eigen::Vector3d directions[] = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                          Eigen::Vector3d::UnitZ(),
                                          Eigen::Vector3d(1, -2, 0.5).normalized()};
    for (const Eigen::Vector3d& direction : directions) {
      const ViewSpec view{direction, bounds, 72};
      ViewSpec opposite = view;
      opposite.direction = -direction;
      for (const DepthUse use : {DepthUse::Fresh, DepthUse::SharedFirst, DepthUse::SharedSecond}) {
        backend.beginPass(use == DepthUse::SharedSecond ? opposite : view, use);
        for (ObjectId o = 0; o < boxes.size(); ++o) {
          backend.queryBoxes(o, boxes[o]);
          backend.writeBoxes(o, boxes[o]);
        }
        if (use != DepthUse::SharedFirst) fetchInto(backend, out);
      }
    }
    readBuffer(backend, 72, out);
  };
  for (bool conservative : {true, false}) {
    SCOPED_TRACE(conservative ? "conservative" : "raw");
    expectBothAnswers(expectSameAsPlain(scene, poses, draws, conservative));
  }
}

// A box test whose centre lies under a stored key at or in front of the box's nearest is occluded
// there without a pixel rasterised (a line of sight through the centre leaves the box through a
// face the test draws), in conservative passes only: behind a wall (sixteen boxes, most of them
// drawn before the tests as more are pending than a tile keeps), a grid of boxes of every shape
// is occluded as the plain evaluation finds it, most of them decided so; raw passes, where a pixel
// is covered by its centre, rasterise every test.
TEST(CpuBoxTests, OccludedUnderTheirCentreWithoutRasterising) {
  const SceneGeometry scene = bumpySpheres();
  const std::vector<Pose> poses(scene.objectCount());
  std::vector<OrientedBox> wall;
  for (int i = 0; i < 16; ++i) {
    OrientedBox piece;
    piece.center = Eigen::Vector3d(-1.2 + 0.8 * (i % 4), -1.2 + 0.8 * (i / 4), 0.0);
    piece.halfExtents = Eigen::Vector3d(0.4, 0.4, 0.05);
    wall.push_back(piece);
  }
  std::mt19937 rng(5);
  std::vector<OrientedBox> grid = boxesOfEveryShape(rng, 16);
  for (std::size_t b = 0; b < grid.size(); ++b) {
    grid[b].center = Eigen::Vector3d(-0.9 + 0.6 * (b % 4), -0.9 + 0.6 * (b / 4), 0.0);
    grid[b].halfExtents = grid[b].halfExtents.cwiseMin(0.2);
  }
  CpuEvaluation oneTile{64, true, true};
  oneTile.mostPendingInTile = 7;
  int behindSides = 0;
  for (const double side : {-1.0, 1.0}) {
    std::vector<OrientedBox> tested = grid;
    for (OrientedBox& box : tested) box.center.z() = 0.8 * side;
    const Stream draws = [&](CpuRasterBackend& backend, Outcome& out) {
      const Aabb bounds(Eigen::Vector3d::Constant(-1.6), Eigen::Vector3d::Constant(1.6));
      backend.beginPass({Eigen::Vector3d::UnitZ(), bounds, 64}, DepthUse::Fresh);
      for (const OrientedBox& piece : wall) backend.writeBoxes(0, std::span(&piece, 1));
      backend.queryBoxes(1, tested);
      fetchInto(backend, out);
    };
    const Outcome plainConservative = run(scene, poses, draws, true, kPlain, 1);
    // Behind the wall: every box found occluded by the plain evaluation in a conservative pass.
    const bool behind = std::ranges::count(plainConservative.answers.at(0), 0) == 16;
    behindSides += behind;
    for (bool conservative : {true, false}) {
      SCOPED_TRACE(testing::Message()
                   << (conservative ? "conservative" : "raw") << ", side " << side);
      const Outcome plain =
          conservative ? plainConservative : run(scene, poses, draws, false, kPlain, 1);
      const Outcome demand = run(scene, poses, draws, conservative, oneTile, 1);
      EXPECT_EQ(demand.answers, plain.answers);
      if (!behind) continue;
      EXPECT_EQ(demand.counters.tileTests, 16u);
      if (conservative) {
        EXPECT_GE(demand.counters.tileTestsByBounds, 12u);
        EXPECT_LT(demand.counters.pixelsTested, plain.counters.pixelsTested);
      } else {
        EXPECT_EQ(demand.counters.tileTestsByBounds, 0u);
        EXPECT_GT(demand.counters.pixelsTested, 0u);
      }
    }
  }
  EXPECT_EQ(behindSides, 1) << "one side of the wall is behind it";
}

TEST(CpuDemandSettings, RefusesATileSizeOffTheBlockGrid) {
  CpuRasterBackend backend;
  for (int size : {-8, 0, 4, 12, 33, 72})
    EXPECT_THROW(backend.setEvaluation({size, true, true}), InputError) << size;
  EXPECT_NO_THROW(backend.setEvaluation({24, true, true}));
  EXPECT_NO_THROW(backend.setEvaluation({64, true, false}));
  // The plain evaluation draws whole tiles of any size.
  EXPECT_NO_THROW(backend.setEvaluation({0, false, false}));
  EXPECT_NO_THROW(backend.setEvaluation({800, false, false}));
}

}  // namespace
}  // namespace cdb::demand_evaluation_test
