// The cpu backend beyond the contract suites: answers and counters that do not depend on the
// thread count (tiles run concurrently at fetch), passes that go on after a fetch, its renderer
// string, and its counters of pixels visited.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "culling/visibility/cpu/CpuRasterBackend.h"
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
