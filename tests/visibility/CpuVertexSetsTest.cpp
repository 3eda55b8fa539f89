// The cpu backend's vertex sets (CpuVertexSets): which commands share one (one mesh, one matrix,
// one pixel grid), and that what a set keeps per mesh chunk (binning's part bounds) is made once
// for all of them, by a thread that finds them being made into its own copy.
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <array>
#include <atomic>
#include <vector>

#include "culling/visibility/cpu/CpuPassSpace.h"
#include "culling/visibility/cpu/CpuVertexSets.h"
#include "tests/visibility/GlTestSupport.h"

namespace cdb::vertex_sets_test {
namespace {

// A strip of `n` triangles (n / 64 chunks and more).
Mesh stripMesh(int n) {
  Mesh m;
  m.name = "strip";
  for (int i = 0; i < n + 2; ++i)
    m.vertices.emplace_back(0.01f * static_cast<float>(i), static_cast<float>(i % 2), 0.5f);
  for (int i = 0; i < n; ++i) {
    const auto v = static_cast<std::uint32_t>(i);
    m.triangles.push_back(i % 2 == 0 ? Triangle{v, v + 1, v + 2} : Triangle{v + 1, v, v + 2});
  }
  return m;
}

ScreenMatrix matrix(double scale) {
  ScreenMatrix m = ScreenMatrix::Zero();
  m(0, 0) = m(1, 1) = scale;
  m(2, 2) = 1.0;
  return m;
}

// A recording of passes (resolution, margin), each with the commands (matrix scale) given.
struct Draw {
  int resolution;
  double margin;
  double scale;
};
CpuRecording recordingOf(const std::vector<std::vector<Draw>>& passes, std::uint32_t triangles) {
  CpuRecording r;
  for (const auto& draws : passes) {
    CpuPass& pass = r.passes.emplace_back();
    pass.raster.resolution = draws.front().resolution;
    pass.raster.marginPx = draws.front().margin;
    pass.firstCommand = static_cast<std::uint32_t>(r.commands.size());
    for (const Draw& d : draws) {
      CpuCommand& c = r.commands.emplace_back();
      c.role = r.commands.size() % 2 == 0 ? CpuCommand::Role::Write : CpuCommand::Role::Test;
      c.count = triangles;
      c.toScreen = matrix(d.scale);
    }
  }
  r.close();
  return r;
}

class CpuVertexSetsTest : public ::testing::Test {
 protected:
  static constexpr int kTriangles = 300;  // 5 chunks, the last of 44 triangles (11 parts)
  SceneGeometry scene = test::sceneOf({stripMesh(kTriangles)});
  std::vector<CpuMeshBounds> bounds = meshBoundsOf(scene);
};

TEST_F(CpuVertexSetsTest, CommandsShareASetOnlyWithTheSameMatrixAndPixelGrid) {
  CpuRecording r = recordingOf({{{64, 0.01, 10.0}, {64, 0.01, 10.0}, {64, 0.01, 20.0}},
                                {{64, 0.01, 10.0}},
                                {{128, 0.01, 10.0}},
                                {{64, 0.02, 10.0}}},
                               kTriangles);
  CpuVertexSets sets;
  sets.assign(r, bounds);
  const auto set = [&](int i) { return r.commands[static_cast<std::size_t>(i)].vertexSet; };
  EXPECT_EQ(set(0), set(1));  // a test and a write of one matrix in one pass
  EXPECT_EQ(set(0), set(3));  // the same in a later pass of the same grid
  EXPECT_NE(set(0), set(2));  // another matrix
  EXPECT_NE(set(0), set(4));  // another resolution
  EXPECT_NE(set(0), set(5));  // another coverage margin
  EXPECT_NE(set(4), set(5));
}

TEST_F(CpuVertexSetsTest, PartBoundsAreMadeOncePerSetAndChunk) {
  CpuRecording r =
      recordingOf({{{64, 0.01, 10.0}, {64, 0.01, 10.0}, {64, 0.01, 20.0}}}, kTriangles);
  CpuVertexSets sets;
  sets.assign(r, bounds);
  const std::size_t meshParts = bounds[0].parts.size();
  ASSERT_EQ(meshParts, 19u);  // 300 triangles in parts of 16
  int made = 0;
  std::array<CpuPartScreenBounds, CpuVertexSets::kChunkParts> own;
  std::vector<std::pair<std::size_t, std::size_t>> asked;
  const auto make = [&](std::size_t first, std::size_t count, CpuPartScreenBounds* out) {
    ++made;
    asked.emplace_back(first, count);
    for (std::size_t k = 0; k < count; ++k) out[k].rect = {static_cast<int>(first + k), 0, 0, 0};
  };
  const CpuPartScreenBounds* first = sets.parts(r.commands[0], 4, meshParts, make, own);
  EXPECT_EQ(made, 1);
  ASSERT_EQ(asked.back(), (std::pair<std::size_t, std::size_t>{16, 3}));  // the last chunk's 3
  // The write of the same set reads what the test's binning made.
  EXPECT_EQ(sets.parts(r.commands[1], 4, meshParts, make, own), first);
  EXPECT_EQ(made, 1);
  EXPECT_EQ(first[2].rect.x0, 18);
  // Another chunk, and another set, are made on their own.
  (void)sets.parts(r.commands[1], 0, meshParts, make, own);
  EXPECT_EQ(asked.back(), (std::pair<std::size_t, std::size_t>{0, 4}));
  EXPECT_NE(sets.parts(r.commands[2], 4, meshParts, make, own), first);
  EXPECT_EQ(made, 3);
  // A new recording starts over.
  sets.assign(r, bounds);
  (void)sets.parts(r.commands[0], 4, meshParts, make, own);
  EXPECT_EQ(made, 4);
}

TEST_F(CpuVertexSetsTest, ThreadsAskingAtOnceGetMadeChunks) {
  CpuRecording r = recordingOf({{{64, 0.01, 10.0}, {64, 0.01, 10.0}}}, kTriangles);
  CpuVertexSets sets;
  sets.assign(r, bounds);
  const std::size_t meshParts = bounds[0].parts.size();
  const auto make = [](std::size_t first, std::size_t count, CpuPartScreenBounds* out) {
    for (std::size_t k = 0; k < count; ++k) out[k].rect.x0 = static_cast<int>(first + k);
  };
  std::atomic<int> wrong{0};
  tbb::parallel_for(0, 2000, [&](int i) {
    const auto chunk = static_cast<std::uint32_t>(i % 5);
    const CpuCommand& c = r.commands[static_cast<std::size_t>(i % 2)];
    std::array<CpuPartScreenBounds, CpuVertexSets::kChunkParts> own;
    if (sets.parts(c, chunk, meshParts, make, own)[0].rect.x0 != static_cast<int>(chunk) * 4)
      ++wrong;  // made before it is read, by this thread or another
  });
  EXPECT_EQ(wrong.load(), 0);
  // Every chunk's bounds are the set's now: nothing is made again.
  int made = 0;
  std::array<CpuPartScreenBounds, CpuVertexSets::kChunkParts> own;
  for (std::uint32_t chunk = 0; chunk < 5; ++chunk)
    (void)sets.parts(
        r.commands[0], chunk, meshParts,
        [&](std::size_t, std::size_t, CpuPartScreenBounds*) { ++made; }, own);
  EXPECT_EQ(made, 0);
}

}  // namespace
}  // namespace cdb::vertex_sets_test
