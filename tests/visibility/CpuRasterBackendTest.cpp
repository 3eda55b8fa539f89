// The cpu backend beyond the contract suites: answers and counters that do not depend on the
// thread count (tiles run concurrently at fetch), passes that go on after a fetch, its renderer
// string, and its counters of pixels visited.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "culling/visibility/cpu/CpuMeshBounds.h"
#include "culling/visibility/cpu/CpuRasterBackend.h"
#include "scenes/ProceduralMeshes.h"
#include "tests/visibility/GlTestSupport.h"

namespace cdb {
namespace {

// Small random meshes (a few triangles each) and random poses, so that passes overlap a lot.
SceneGeometry randomScene(unsigned seed, int objects) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  std::vector<Mesh> meshes;
  for (int o = 0; o < objects; ++o) {
    Mesh m;
    m.name = "random";
    for (int v = 0; v < 9; ++v) m.vertices.push_back(Eigen::Vector3f(u(rng), u(rng), u(rng)) * 0.3f);
    m.triangles = {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}, {0, 4, 8}};
    meshes.push_back(m);
  }
  return test::sceneOf(std::move(meshes));
}

std::vector<Pose> randomPoses(unsigned seed, std::size_t n) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Pose> poses(n);
  for (Pose& p : poses) {
    p.rotation = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized();
    p.translation = Eigen::Vector3d(u(rng), u(rng), u(rng));
  }
  return poses;
}

struct Recorded {
  std::vector<std::vector<std::uint8_t>> answers;  // per fetch
  VisibilityCounters counters;
};

// Every kind of draw in every kind of pass, over three fetches; a SharedSecond pass begins
// after its SharedFirst was fetched, and draws go on in a pass after a fetch.
Recorded exercise(int threads, bool conservative) {
  const SceneGeometry scene = randomScene(5, 40);
  CpuRasterBackend backend(VisibilityOptions{conservative, 1e-5, threads});
  // Without the early-out, so that the work done does not depend on which tile finds a piece
  // occluded first either.
  backend.setEvaluation({32, true, false});
  backend.attachScene(scene);
  backend.setPoses(randomPoses(6, scene.objectCount()));
  const Aabb bounds(Eigen::Vector3d::Constant(-1.5), Eigen::Vector3d::Constant(1.5));
  Recorded run;
  std::vector<std::uint8_t> answers;
  OrientedBox box;
  box.halfExtents = Eigen::Vector3d(0.1, 0.2, 0.05);
  const std::uint32_t listed[] = {3, 1};
  for (int round = 0; round < 3; ++round) {
    for (int pass = 0; pass < 6; ++pass) {
      const Eigen::Vector3d direction = Eigen::Vector3d::Unit(pass % 3) * (pass < 3 ? 1.0 : -1.0);
      const DepthUse use =
          pass % 2 == 0 ? (round == 1 ? DepthUse::SharedFirst : DepthUse::Fresh)
                        : (round == 1 ? DepthUse::SharedSecond : DepthUse::Fresh);
      backend.beginPass({direction, bounds, 64 + 150 * (pass / 2)}, use);
      for (ObjectId o = 0; o < scene.objectCount(); ++o) {
        backend.queryRange(test::wholeOf(scene, o));
        backend.queryTriangles(test::wholeOf(scene, o));
        backend.queryTriangles(o, listed);
        backend.queryBox(o, box);
        if (o % 3 == 0) backend.writeBox(o, box);
        if (o % 3 == 1) backend.writeTriangles(o, listed);
        if (o % 3 == 2) backend.writeRange(test::wholeOf(scene, o));
      }
      if (round == 1 && pass % 2 == 0) {  // fetch between SharedFirst and SharedSecond
        backend.fetchResults(answers);
        run.answers.push_back(answers);
      }
    }
    backend.fetchResults(answers);
    run.answers.push_back(answers);
    // The last pass goes on after the fetch.
    backend.queryRange(test::wholeOf(scene, 0));
    backend.writeRange(test::wholeOf(scene, 1));
    backend.queryRange(test::wholeOf(scene, 2));
  }
  backend.fetchResults(answers);
  run.answers.push_back(answers);
  run.counters = backend.counters();
  return run;
}

TEST(CpuRasterBackend, AnswersAndCountersDoNotDependOnThreads) {
  for (bool conservative : {true, false}) {
    const Recorded one = exercise(1, conservative);
    for (int threads : {2, 3, 8}) {
      const Recorded many = exercise(threads, conservative);
      EXPECT_EQ(many.answers, one.answers) << threads << " threads";
      const VisibilityCounters& a = one.counters;
      const VisibilityCounters& b = many.counters;
      EXPECT_EQ(a.queries, b.queries);
      EXPECT_EQ(a.draws, b.draws);
      EXPECT_EQ(a.trianglesDrawn, b.trianglesDrawn);
      EXPECT_EQ(a.passes, b.passes);
      EXPECT_EQ(a.depthClears, b.depthClears);
      EXPECT_EQ(a.fetches, b.fetches);
      EXPECT_EQ(a.pixelsTested, b.pixelsTested);
      EXPECT_EQ(a.pixelsWritten, b.pixelsWritten);
    }
    // Not everything visible, not everything occluded: the scene exercises both.
    int visible = 0, total = 0;
    for (const auto& f : one.answers)
      for (std::uint8_t v : f) visible += v, ++total;
    EXPECT_GT(visible, 0);
    EXPECT_LT(visible, total);
    EXPECT_GT(one.counters.pixelsTested, 0u);
    EXPECT_GT(one.counters.pixelsWritten, 0u);
  }
}

TEST(CpuRasterBackend, PassGoesOnAfterAFetch) {
  const SceneGeometry scene = test::sceneOf(
      {test::squareMesh(0, 0, 0, 1), test::squareMesh(0, 0, 2, 1), test::squareMesh(0, 0, -2, 1)});
  CpuRasterBackend backend;
  backend.attachScene(scene);
  backend.setPoses(test::identityPoses(scene.objectCount()));
  backend.beginPass({Eigen::Vector3d::UnitZ(),
                     Aabb(Eigen::Vector3d(-2, -2, -3), Eigen::Vector3d(2, 2, 3)), 64},
                    DepthUse::Fresh);
  backend.writeRange(test::wholeOf(scene, 0));
  std::vector<std::uint8_t> answers;
  backend.fetchResults(answers);
  EXPECT_TRUE(answers.empty());
  const QueryIndex behind = backend.queryRange(test::wholeOf(scene, 1));
  const QueryIndex front = backend.queryRange(test::wholeOf(scene, 2));
  backend.fetchResults(answers);
  ASSERT_EQ(answers.size(), 2u);
  EXPECT_EQ(answers[behind], 0);
  EXPECT_EQ(answers[front], 1);
  EXPECT_LT(backend.storedDepth(32, 32), 1.f);  // A's depth is there
  EXPECT_EQ(backend.storedDepth(0, 0), 1.f);    // the clear beside it
}

// A tile's walk stops after its last test still open: a write issued after every test of a fetch
// is not made pending there, in a pass that ends with the fetch (a fresh pass after it) or in one
// that goes on after it, where it is walked before the tests that follow and hides what lies
// behind it.
TEST(CpuRasterBackend, WritesAfterTheLastTestAreWalkedOnlyWhereAPassGoesOn) {
  // A at z = 0 in front of B at z = 2 (the view looks along +z: nearer is smaller z).
  const SceneGeometry scene =
      test::sceneOf({test::squareMesh(0, 0, 0, 1), test::squareMesh(0, 0, 2, 1)});
  const ViewSpec view{Eigen::Vector3d::UnitZ(),
                      Aabb(Eigen::Vector3d(-2, -2, -3), Eigen::Vector3d(2, 2, 3)), 64};
  for (const bool goesOn : {false, true}) {
    SCOPED_TRACE(goesOn ? "the pass goes on after the fetch" : "a fresh pass after the fetch");
    CpuRasterBackend backend;
    backend.attachScene(scene);
    backend.setPoses(test::identityPoses(scene.objectCount()));
    backend.beginPass(view, DepthUse::Fresh);
    const QueryIndex first = backend.queryRange(test::wholeOf(scene, 1));
    backend.writeRange(test::wholeOf(scene, 0));
    std::vector<std::uint8_t> answers;
    backend.fetchResults(answers);
    ASSERT_EQ(answers.size(), 1u);
    EXPECT_EQ(answers[first], 1);  // nothing drawn before it
    EXPECT_EQ(backend.counters().tileWrites, 0u);
    EXPECT_GT(backend.counters().tileTests, 0u);
    if (!goesOn) backend.beginPass(view, DepthUse::Fresh);
    const QueryIndex second = backend.queryRange(test::wholeOf(scene, 1));
    backend.fetchResults(answers);
    ASSERT_EQ(answers.size(), 1u);
    // Going on, B is tested behind A's depths; in a fresh pass against the clear value.
    EXPECT_EQ(answers[second], goesOn ? 0 : 1);
    EXPECT_EQ(backend.counters().tileWrites > 0, goesOn);
  }
}

// A 20 x 20 grid of squares (two triangles each, row by row) in the plane z = z0 over [-1, 1]^2.
Mesh gridMesh(float z0) {
  Mesh m;
  m.name = "grid";
  constexpr int kCells = 20;
  for (int j = 0; j <= kCells; ++j)
    for (int i = 0; i <= kCells; ++i)
      m.vertices.emplace_back(-1.f + 2.f * i / kCells, -1.f + 2.f * j / kCells, z0);
  for (int j = 0; j < kCells; ++j)
    for (int i = 0; i < kCells; ++i) {
      const std::uint32_t a = j * (kCells + 1) + i, b = a + 1, c = a + kCells + 1, d = c + 1;
      m.triangles.push_back({a, b, d});
      m.triangles.push_back({a, d, c});
    }
  return m;
}

// The backend draws a mesh's triangles in an order of its own (CpuMeshBounds' draw order), so a
// batch's answers are renumbered back: each triangle's answer is the same however the triangles
// were issued (whole, listed in any order and with repeats, as part of the mesh, or alone).
TEST(CpuRasterBackend, BatchAnswersFollowTheIssuedOrder) {
  // The grid behind a square that hides its half x < 0.
  const SceneGeometry scene = test::sceneOf({test::squareMesh(-1, 0, 0, 1), gridMesh(1)});
  const std::vector<std::uint32_t> order = drawOrderOf(scene.meshes[1]);
  const std::size_t n = scene.meshes[1].triangleCount();
  std::vector<std::uint32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (std::uint32_t t = 0; t < n; ++t) ASSERT_EQ(sorted[t], t);  // a permutation
  ASSERT_FALSE(std::is_sorted(order.begin(), order.end()));      // and not the mesh's own order

  for (int threads : {1, 2}) {
    CpuRasterBackend backend(VisibilityOptions{true, 1e-5, threads});
    backend.attachScene(scene);
    backend.setPoses(test::identityPoses(scene.objectCount()));
    backend.beginPass({Eigen::Vector3d::UnitZ(),
                       Aabb(Eigen::Vector3d(-2, -2, -1), Eigen::Vector3d(2, 2, 2)), 128},
                      DepthUse::Fresh);
    backend.writeRange(test::wholeOf(scene, 0));
    const QueryIndex whole = backend.queryTriangles(test::wholeOf(scene, 1));
    std::vector<std::uint32_t> listed(n);
    std::iota(listed.begin(), listed.end(), 0u);
    std::shuffle(listed.begin(), listed.end(), std::mt19937(7));
    const QueryIndex shuffledOnce = backend.queryTriangles(1, listed);
    listed.push_back(listed[5]);
    const QueryIndex shuffled = backend.queryTriangles(1, listed);
    const QueryIndex part = backend.queryTriangles(MeshRange{1, 100, 300});
    std::vector<QueryIndex> alone(n);
    for (std::uint32_t t = 0; t < n; ++t) {
      const std::uint32_t one[] = {t};
      alone[t] = backend.queryTriangles(1, one);
    }
    std::vector<std::uint8_t> answers;
    backend.fetchResults(answers);

    int visible = 0;
    for (std::uint32_t t = 0; t < n; ++t) {
      const std::uint8_t a = answers[alone[t]];
      visible += a;
      EXPECT_EQ(answers[whole + t], a) << "triangle " << t;
      if (t >= 100 && t < 400) {
        EXPECT_EQ(answers[part + t - 100], a) << "triangle " << t;
      }
    }
    for (std::size_t k = 0; k < listed.size(); ++k) {
      EXPECT_EQ(answers[shuffled + k], answers[alone[listed[k]]]) << "entry " << k;
      if (k < n) {
        EXPECT_EQ(answers[shuffledOnce + k], answers[alone[listed[k]]]) << "entry " << k;
      }
    }
    // Half hidden, half in view (the column at x = 0 hidden too, conservatively).
    EXPECT_GT(visible, static_cast<int>(n) / 3);
    EXPECT_LT(visible, static_cast<int>(n) / 2);
    // Each triangle of the hidden half is occluded, of the other half visible.
    for (std::uint32_t t = 0; t < n; ++t) {
      const float cx = scene.meshes[1].vertices[scene.meshes[1].triangles[t][0]].x();
      if (cx < -0.15f) {
        EXPECT_EQ(answers[alone[t]], 0) << "triangle " << t;
      }
      if (cx > 0.15f) {
        EXPECT_EQ(answers[alone[t]], 1) << "triangle " << t;
      }
    }
  }
}

// The draw order is the Morton one where it makes chunks more compact (a grid listed row by row,
// whose chunks are strips), the mesh's own where not (a torus listed ring by ring around its tube:
// each chunk is already a band), and a permutation either way.
TEST(CpuRasterBackend, DrawOrderKeepsTheMoreCompactChunks) {
  const Mesh grid = gridMesh(0);
  EXPECT_EQ(chosenDrawOrder(grid), drawOrderOf(grid));
  const Mesh torus = makeTorus(0.5, 0.2, 20, 20);
  std::vector<std::uint32_t> own(torus.triangleCount());
  std::iota(own.begin(), own.end(), 0u);
  EXPECT_EQ(chosenDrawOrder(torus), own);
  EXPECT_NE(drawOrderOf(torus), own);
}

TEST(CpuRasterBackend, NamesItsInstructionSetAndThreads) {
  CpuRasterBackend backend(VisibilityOptions{true, 1e-5, 3});
  EXPECT_EQ(backend.name(), "cpu");
  EXPECT_EQ(backend.maxResolution(), 16384);
  const std::string r = backend.renderer();
  EXPECT_NE(r.find("cpu depth rasteriser (Highway "), std::string::npos) << r;
  EXPECT_NE(r.find(", 3 threads)"), std::string::npos) << r;
}

}  // namespace
}  // namespace cdb
