// What the cpu backend does to save work: write footprints (which writes share one: the same
// triangles, matrix and pass set-up, drawn more than once in a frame) and pieces decided by the
// tiles under their screen bounds. Each leaves every answer and every stored depth as drawing
// every triangle does.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "culling/visibility/cpu/CpuRasterBackend.h"
#include "tests/visibility/GlTestSupport.h"

namespace cdb {
namespace {

// A closed sphere of `rings` x `segments` quads (two triangles each, caps of triangles), wound
// counter-clockwise seen from outside, its vertices moved radially at random so that it is not
// convex: many small triangles that overlap in depth.
Mesh bumpySphere(unsigned seed, int rings, int segments) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> bump(0.7f, 1.0f);
  Mesh m;
  m.name = "bumpy sphere";
  m.vertices.emplace_back(0.f, 0.f, bump(rng));  // north pole
  for (int r = 1; r < rings; ++r) {
    const double theta = std::numbers::pi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double phi = 2 * std::numbers::pi * s / segments;
      const float radius = bump(rng);
      m.vertices.emplace_back(radius * std::sin(theta) * std::cos(phi),
                              radius * std::sin(theta) * std::sin(phi), radius * std::cos(theta));
    }
  }
  m.vertices.emplace_back(0.f, 0.f, -bump(rng));  // south pole
  const auto at = [&](int ring, int s) {          // ring 1 .. rings - 1
    return static_cast<std::uint32_t>(1 + (ring - 1) * segments + (s % segments));
  };
  const auto south = static_cast<std::uint32_t>(m.vertices.size() - 1);
  for (int s = 0; s < segments; ++s) {
    m.triangles.push_back({0, at(1, s), at(1, s + 1)});
    for (int r = 1; r + 1 < rings; ++r) {
      m.triangles.push_back({at(r, s), at(r + 1, s), at(r + 1, s + 1)});
      m.triangles.push_back({at(r, s), at(r + 1, s + 1), at(r, s + 1)});
    }
    m.triangles.push_back({at(rings - 1, s), south, at(rings - 1, s + 1)});
  }
  return m;
}

SceneGeometry sphereScene(int objects) {
  std::vector<Mesh> meshes;
  // Enough triangles (> 500) that their writes get footprints.
  for (int o = 0; o < objects; ++o) meshes.push_back(bumpySphere(11 + o, 18 + o % 3, 16));
  return test::sceneOf(std::move(meshes));
}

std::vector<Pose> posesAround(unsigned seed, std::size_t n) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Pose> poses(n);
  for (Pose& p : poses) {
    p.rotation = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized();
    p.translation = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 1.2;
  }
  return poses;
}

struct DrawsOutcome {
  std::vector<std::vector<std::uint8_t>> answers;  // per fetch
  std::vector<std::size_t> footprints;             // per fetch
  std::vector<float> lastBuffer;                   // the buffer the last pass left
  VisibilityCounters counters;
};

// CULLIDE's draws along each axis (pass 1 tests and writes every object in order, pass 2 in
// reverse, fresh depth, one fetch), then a triangle level (per member a batch of tests, then
// its listed triangles written), then a pair of depth-sorted passes (one clear, opposite views)
// and node boxes written in both passes of a view.
DrawsOutcome cullideDraws(CpuRasterBackend::WorkSavers savers, bool conservative, int resolution,
                          int threads) {
  const SceneGeometry scene = sphereScene(9);
  CpuRasterBackend backend(VisibilityOptions{conservative, 1e-5, threads});
  backend.setWorkSavers(savers);
  backend.attachScene(scene);
  backend.setPoses(posesAround(3, scene.objectCount()));
  const Aabb bounds(Eigen::Vector3d::Constant(-2.5), Eigen::Vector3d::Constant(2.5));
  DrawsOutcome out;
  std::vector<std::uint8_t> answers;
  const auto fetch = [&] {
    backend.fetchResults(answers);
    out.answers.push_back(answers);
    out.footprints.push_back(backend.lastFootprintsUsed());
  };
  const auto objects = static_cast<ObjectId>(scene.objectCount());
  for (int axis = 0; axis < 3; ++axis) {
    const ViewSpec view{Eigen::Vector3d::Unit(axis), bounds, resolution};
    backend.beginPass(view, DepthUse::Fresh);
    for (ObjectId o = 0; o < objects; ++o) {
      backend.queryRange(test::wholeOf(scene, o));
      backend.writeRange(test::wholeOf(scene, o));
    }
    backend.beginPass(view, DepthUse::Fresh);
    for (ObjectId o = objects; o-- > 0;) {
      backend.queryRange(test::wholeOf(scene, o));
      backend.writeRange(test::wholeOf(scene, o));
    }
    fetch();
  }
  // Triangle level: four of every five triangles of each object.
  std::vector<std::vector<std::uint32_t>> lists(objects);
  for (ObjectId o = 0; o < objects; ++o)
    for (std::uint32_t t = 0; t < scene.meshOf(o).triangleCount(); ++t)
      if ((t + o) % 5 != 0) lists[o].push_back(t);
  const ViewSpec side{Eigen::Vector3d(1, 1, 0).normalized(), bounds, resolution};
  for (int pass = 0; pass < 2; ++pass) {
    backend.beginPass(side, DepthUse::Fresh);
    for (ObjectId i = 0; i < objects; ++i) {
      const ObjectId o = pass == 0 ? i : objects - 1 - i;
      backend.queryTriangles(o, lists[o]);
      backend.writeTriangles(o, lists[o]);
    }
  }
  fetch();
  // Depth-sorted passes (no write recurs) and boxes.
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
  fetch();
  std::vector<OrientedBox> boxes(70);  // enough for a footprint
  for (std::size_t b = 0; b < boxes.size(); ++b) {
    boxes[b].center = Eigen::Vector3d(0.02 * b - 0.7, -0.2 + 0.01 * b, 0.01 * b);
    boxes[b].halfExtents = Eigen::Vector3d(0.05, 0.03 + 0.002 * b, 0.04);
  }
  for (int pass = 0; pass < 2; ++pass) {
    backend.beginPass(up, DepthUse::Fresh);
    for (ObjectId i = 0; i < objects; ++i) {
      const ObjectId o = pass == 0 ? i : objects - 1 - i;
      backend.queryBoxes(o, boxes);
      backend.writeBoxes(o, boxes);
    }
  }
  fetch();
  for (int y = 0; y < resolution; ++y)
    for (int x = 0; x < resolution; ++x) out.lastBuffer.push_back(backend.storedDepth(x, y));
  out.counters = backend.counters();
  return out;
}

using Savers = CpuRasterBackend::WorkSavers;
constexpr Savers kNone{false, false};
constexpr Savers kAll{true, true};

TEST(CpuWorkSavers, LeaveWhatDrawingEveryTriangleLeaves) {
  for (bool conservative : {true, false})
    for (int resolution : {64, 256, 601}) {
      SCOPED_TRACE(testing::Message()
                   << (conservative ? "conservative" : "raw") << " at " << resolution << " px");
      const DrawsOutcome rasterised = cullideDraws(kNone, conservative, resolution, 1);
      for (const Savers savers : {Savers{true, false}, Savers{false, true}, kAll}) {
        SCOPED_TRACE(testing::Message() << "footprints " << savers.writeFootprints
                                        << ", decided by bounds " << savers.decideByBounds);
        const DrawsOutcome saved = cullideDraws(savers, conservative, resolution, 1);
        EXPECT_EQ(saved.answers, rasterised.answers);
        EXPECT_EQ(saved.lastBuffer, rasterised.lastBuffer);
        EXPECT_EQ(saved.counters.trianglesDrawn, rasterised.counters.trianglesDrawn);
        EXPECT_EQ(saved.counters.queries, rasterised.counters.queries);
      }
      // Both answers occur, so the comparison decides something.
      int visible = 0, total = 0;
      for (const auto& fetch : rasterised.answers)
        for (std::uint8_t v : fetch) visible += v, ++total;
      EXPECT_GT(visible, 0);
      EXPECT_LT(visible, total);
      // The buffer holds more than its clear value.
      EXPECT_NE(std::ranges::min(rasterised.lastBuffer), std::ranges::max(rasterised.lastBuffer));
    }
}

// A wall (a square facing the view) written first, then small spheres scattered over and around
// it, some in front, some behind, some through it, each tested and written, then each tested
// again: many pieces whose screen bounds lie on tiles the wall decides, and many whose bounds end
// near a tile's edge.
struct WallOutcome {
  std::vector<std::uint8_t> answers;
  std::vector<float> buffer;
};
WallOutcome wallAndSpheres(Savers savers, bool conservative, int resolution, unsigned seed) {
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
  CpuRasterBackend backend(VisibilityOptions{conservative, 1e-5, 1});
  backend.setWorkSavers(savers);
  backend.attachScene(scene);
  backend.setPoses(poses);
  const Aabb bounds(Eigen::Vector3d(-1.5, -1.5, -0.5), Eigen::Vector3d(1.5, 1.5, 0.5));
  const auto objects = static_cast<ObjectId>(scene.objectCount());
  backend.beginPass({Eigen::Vector3d::UnitZ(), bounds, resolution}, DepthUse::Fresh);
  backend.writeRange(test::wholeOf(scene, 0));
  for (ObjectId o = 1; o < objects; ++o) {
    backend.queryRange(test::wholeOf(scene, o));
    backend.writeRange(test::wholeOf(scene, o));
  }
  for (ObjectId o = 1; o < objects; ++o) backend.queryRange(test::wholeOf(scene, o));
  WallOutcome out;
  backend.fetchResults(out.answers);
  for (int y = 0; y < resolution; ++y)
    for (int x = 0; x < resolution; ++x) out.buffer.push_back(backend.storedDepth(x, y));
  return out;
}

TEST(CpuWorkSavers, PiecesDecidedByBoundsAsByTheirTriangles) {
  int visible = 0, total = 0;
  for (bool conservative : {true, false})
    for (int resolution : {64, 100, 257})
      for (unsigned seed : {1u, 2u, 3u}) {
        SCOPED_TRACE(testing::Message() << (conservative ? "conservative" : "raw") << " at "
                                        << resolution << " px, seed " << seed);
        const WallOutcome drawn = wallAndSpheres(kNone, conservative, resolution, seed);
        const WallOutcome decided =
            wallAndSpheres(Savers{false, true}, conservative, resolution, seed);
        EXPECT_EQ(decided.answers, drawn.answers);
        EXPECT_EQ(decided.buffer, drawn.buffer);
        for (std::uint8_t v : drawn.answers) visible += v, ++total;
      }
  EXPECT_GT(visible, total / 10);
  EXPECT_LT(visible, total - total / 10);
}

TEST(CpuWorkSavers, RecurringWritesShareOneFootprint) {
  const DrawsOutcome merged = cullideDraws(kAll, true, 128, 1);
  // Each axis: every object's write recurs once (9 objects); the triangle level's lists recur
  // (9); depth-sorted passes look opposite ways (none); the node boxes recur (9).
  EXPECT_EQ(merged.footprints, (std::vector<std::size_t>{9, 9, 9, 9, 0, 9}));
  const DrawsOutcome rasterised = cullideDraws(kNone, true, 128, 1);
  EXPECT_EQ(rasterised.footprints, (std::vector<std::size_t>{0, 0, 0, 0, 0, 0}));
}

TEST(CpuWorkSavers, WritesThatDifferShareNoFootprint) {
  const SceneGeometry scene = sphereScene(2);
  CpuRasterBackend backend(VisibilityOptions{true, 1e-5, 1});
  backend.attachScene(scene);
  backend.setPoses(posesAround(4, 2));
  const Aabb bounds(Eigen::Vector3d::Constant(-2.5), Eigen::Vector3d::Constant(2.5));
  std::vector<std::uint8_t> answers;
  // Two lists of 400 triangles, differing in the last.
  std::vector<std::uint32_t> a(400), b(400);
  for (std::uint32_t t = 0; t < 400; ++t) a[t] = b[t] = t;
  b.back() = 450;
  const auto footprintsOf = [&](auto&& draws) {
    draws();
    backend.fetchResults(answers);
    return backend.lastFootprintsUsed();
  };
  // Another list of the same object.
  EXPECT_EQ(footprintsOf([&] {
              backend.beginPass({Eigen::Vector3d::UnitX(), bounds, 100}, DepthUse::Fresh);
              backend.writeTriangles(0, a);
              backend.writeTriangles(0, b);
            }),
            0u);
  // Another view, another resolution, another object with the same mesh range.
  EXPECT_EQ(footprintsOf([&] {
              backend.beginPass({Eigen::Vector3d::UnitX(), bounds, 100}, DepthUse::Fresh);
              backend.writeRange(test::wholeOf(scene, 0));
              backend.beginPass({Eigen::Vector3d::UnitY(), bounds, 100}, DepthUse::Fresh);
              backend.writeRange(test::wholeOf(scene, 0));
              backend.beginPass({Eigen::Vector3d::UnitX(), bounds, 101}, DepthUse::Fresh);
              backend.writeRange(test::wholeOf(scene, 0));
              backend.writeRange(test::wholeOf(scene, 1));
            }),
            0u);
  // The same list twice, and the same range three times: two footprints.
  EXPECT_EQ(footprintsOf([&] {
              backend.beginPass({Eigen::Vector3d::UnitX(), bounds, 100}, DepthUse::Fresh);
              backend.writeTriangles(0, a);
              backend.writeRange(test::wholeOf(scene, 1));
              backend.writeRange(test::wholeOf(scene, 1));
              backend.beginPass({Eigen::Vector3d::UnitX(), bounds, 100}, DepthUse::Fresh);
              backend.writeTriangles(0, a);
              backend.writeRange(test::wholeOf(scene, 1));
            }),
            2u);
}

TEST(CpuWorkSavers, FootprintsKeptAfterAFetchUntilThePosesChange) {
  const SceneGeometry scene = sphereScene(2);
  CpuRasterBackend backend(VisibilityOptions{true, 1e-5, 1});
  backend.attachScene(scene);
  const std::vector<Pose> poses = posesAround(4, 2);
  backend.setPoses(poses);
  const ViewSpec view{Eigen::Vector3d::UnitX(),
                      Aabb(Eigen::Vector3d::Constant(-2.5), Eigen::Vector3d::Constant(2.5)), 100};
  std::vector<std::uint8_t> answers;
  const auto drawAndFetch = [&](int writes) {
    backend.beginPass(view, DepthUse::Fresh);
    for (int w = 0; w < writes; ++w) backend.writeRange(test::wholeOf(scene, 0));
    backend.queryRange(test::wholeOf(scene, 1));
    backend.fetchResults(answers);
    return std::pair{backend.lastFootprintsUsed(), backend.lastFootprintsBuilt()};
  };
  EXPECT_EQ(drawAndFetch(2), std::pair(std::size_t{1}, std::size_t{1}));
  // Drawn once after the fetch: from the kept footprint.
  EXPECT_EQ(drawAndFetch(1), std::pair(std::size_t{1}, std::size_t{0}));
  // The same poses again are a new frame: nothing kept.
  backend.setPoses(poses);
  EXPECT_EQ(drawAndFetch(1), std::pair(std::size_t{0}, std::size_t{0}));
}

TEST(CpuWorkSavers, AnswersDoNotDependOnThreads) {
  const DrawsOutcome one = cullideDraws(kAll, true, 200, 1);
  const DrawsOutcome three = cullideDraws(kAll, true, 200, 3);
  EXPECT_EQ(three.answers, one.answers);
  EXPECT_EQ(three.lastBuffer, one.lastBuffer);
  EXPECT_EQ(three.counters.pixelsWritten, one.counters.pixelsWritten);
  EXPECT_EQ(three.counters.pixelsTested, one.counters.pixelsTested);
}

}  // namespace
}  // namespace cdb
