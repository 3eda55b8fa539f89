// Bad meshes referenced from a config (`mesh: {kind: asset}` found through --assets): exit 2, one
// line naming the mesh file and what was expected, no result file.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "tests/reliability/CdbenchProcess.h"

namespace cdb::test {
namespace {

// Two bodies of the asset, no gravity, a tiny sweep: a good mesh runs in a second.
std::string assetConfig(const std::string& asset, const std::string& meshExtra = "") {
  return "environment: meshcheck\n"
         "dynamics: {gravity: [0, 0, 0], time_step: 0.01, frames: 2}\n"
         "bodies:\n"
         "  - name: thing\n"
         "    mesh: {kind: asset, asset: " +
         asset + meshExtra +
         "}\n"
         "    count: 2\n"
         "    collision: box\n"
         "    placement: {region_min: [-3, -3, -3], region_max: [3, 3, 3]}\n"
         "sweep: {resolutions: [64], strategies: [cullide]}\n";
}

constexpr const char* kTetrahedronObj =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
    "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

class BadMesh : public ::testing::Test {
 protected:
  ScratchDir dir;
  std::filesystem::path assets() const { return dir.path() / "assets"; }
  std::filesystem::path out() const { return dir.path() / "out"; }
  std::filesystem::path writeAsset(const std::string& name, const std::string& bytes) const {
    return dir.write("assets/" + name, bytes);
  }
  ProcessResult run(const std::string& asset, const std::string& meshExtra = "") const {
    std::filesystem::create_directories(assets());
    const auto config = dir.write("mesh.yaml", assetConfig(asset, meshExtra));
    return runCdbench({"run", config.string(), "--assets", assets().string(), "--no-truth",
                       "--quiet", "--out", out().string()});
  }
};

// The template itself is sound: what the other tests change is the only thing wrong.
TEST_F(BadMesh, AGoodMeshRuns) {
  writeAsset("tetra.obj", kTetrahedronObj);
  const auto r = run("tetra");
  ASSERT_EQ(r.exitCode, 0) << r.stdErr;
  for (const char* f : kResultFiles) EXPECT_TRUE(std::filesystem::exists(out() / f)) << f;
}

TEST_F(BadMesh, Missing) {
  const auto r = run("nosuchmesh");
  expectCleanFailure(r, 2, out(), {"nosuchmesh", "not found", assets().string()});
}

TEST_F(BadMesh, Unreadable) {
  if (::geteuid() == 0) GTEST_SKIP() << "root reads files whatever their mode";
  const auto file = writeAsset("locked.obj", kTetrahedronObj);
  ASSERT_EQ(::chmod(file.c_str(), 0), 0);
  const auto r = run("locked");
  ::chmod(file.c_str(), 0644);  // so the scratch directory can be removed
  expectCleanFailure(r, 2, out(), {"locked.obj"});
}

// A bad asset file: its name, its bytes, and what the one line must mention.
struct BadAsset {
  const char* name;  // the test's name
  std::string file;  // under the asset folder; the config names it by its stem
  std::string bytes;
  std::vector<std::string> mentions;
};

// A binary PLY of three vertices and one face, `inf` in one coordinate.
std::string plyWithAnInfiniteCoordinate() {
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  const float inf = std::numeric_limits<float>::infinity();
  const float v[9] = {0, 0, 0, 1, 0, 0, 0, inf, 0};
  ply.append(reinterpret_cast<const char*>(v), sizeof v);
  const std::uint8_t n = 3;
  const std::int32_t f[3] = {0, 1, 2};
  ply.append(reinterpret_cast<const char*>(&n), 1);
  ply.append(reinterpret_cast<const char*>(f), sizeof f);
  return ply;
}

// A list length in a binary PLY that the file cannot hold: assimp alone would allocate gigabytes.
std::string plyWithACountBeyondTheFile() {
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uint uint vertex_indices\nend_header\n";
  ply += std::string(36, '\0');
  ply += std::string("\xff\xff\xff\x7f", 4);  // 2^31 - 1 indices announced
  ply += std::string(12, '\0');
  return ply;
}

const BadAsset kBadAssets[] = {
    {"Empty", "empty.obj", "", {"empty.obj", "no triangles", "empty"}},
    {"PointsAndLinesOnly",
     "wire.obj",
     "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1\np 2\nl 1 2\nl 2 3\n",
     {"wire.obj", "no triangles"}},
    {"OnlyDegenerateTriangles",
     "flat.obj",
     "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n",
     {"flat.obj", "no triangles", "degenerate"}},
    {"NanCoordinate",
     "nan.obj",
     "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n",
     {"nan.obj", "expected finite coordinates"}},
    {"InfiniteCoordinateInBinaryPly",
     "inf.ply",
     plyWithAnInfiniteCoordinate(),
     {"inf.ply", "expected finite coordinates"}},
    {"IndexOutOfRange", "index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", {"index.obj"}},
    {"NotAMesh", "text.obj", "this is not a mesh\n\x01\x02\x03", {"text.obj"}},
    {"TruncatedBinaryPly",
     "cut.ply",
     "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
     "property float y\nproperty float z\nelement face 1\n"
     "property list uchar int vertex_indices\nend_header\n\x01\x02",
     {"cut.ply"}},
    // A PLY cut inside its header: assimp alone would loop for ever on it.
    {"PlyHeaderCutShort",
     "header.ply",
     "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n",
     {"header.ply", "end_header"}},
    {"PlyCountBeyondTheFile",
     "huge.ply",
     plyWithACountBeyondTheFile(),
     {"huge.ply", "PLY element 'face'", "does not fit"}},
};

class BadAssetFile : public BadMesh, public ::testing::WithParamInterface<BadAsset> {};

TEST_P(BadAssetFile, ExitsTwoWithOneLine) {
  const BadAsset& bad = GetParam();
  writeAsset(bad.file, bad.bytes);
  const auto r = run(std::filesystem::path(bad.file).stem().string());
  expectCleanFailure(r, 2, out(), bad.mentions);
}

INSTANTIATE_TEST_SUITE_P(Assets, BadAssetFile, ::testing::ValuesIn(kBadAssets),
                         [](const auto& param) { return std::string(param.param.name); });

// Meshes of millions of triangles are accepted up to mesh.max_triangles (8 M by default, see
// configs/README.md) and refused above it; the check is the same at any limit, so it is shown on
// a small one rather than on a file that takes seconds to parse.
TEST_F(BadMesh, MoreTrianglesThanTheLimit) {
  writeAsset("tetra.obj", kTetrahedronObj);
  const auto r = run("tetra", ", max_triangles: 3");
  expectCleanFailure(r, 2, out(), {"tetra.obj", "at most 3 triangles", "max_triangles", "got 4"});
}

TEST_F(BadMesh, MaxTrianglesOutOfRange) {
  writeAsset("tetra.obj", kTetrahedronObj);
  const auto r = run("tetra", ", max_triangles: 0");
  expectCleanFailure(r, 2, out(), {"mesh.yaml:", "max_triangles", "expected an integer in"});
}

}  // namespace
}  // namespace cdb::test
