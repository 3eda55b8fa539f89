// Procedural meshes, the mesh loader (assimp) with its checks and normalisation, and the asset
// path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include "ScratchDir.h"
#include "TestAssets.h"
#include "core/Errors.h"
#include "scenes/AssetFiles.h"
#include "scenes/AssetPath.h"
#include "scenes/MeshLoader.h"
#include "scenes/MeshMeasures.h"
#include "scenes/ProceduralMeshes.h"

namespace cdb {
namespace {

using test::ScopedEnv;
using test::ScratchDir;

Eigen::Vector3d vertex(const Mesh& mesh, std::uint32_t i) {
  return mesh.vertices[i].cast<double>();
}

Eigen::Vector3d normalOf(const Mesh& mesh, const Triangle& t) {
  return (vertex(mesh, t[1]) - vertex(mesh, t[0])).cross(vertex(mesh, t[2]) - vertex(mesh, t[0]));
}

// Closed with consistent winding: every directed edge once, and its reverse once.
void expectClosedAndConsistent(const Mesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  for (const auto& [edge, n] : directed) {
    ASSERT_EQ(n, 1) << "edge " << edge.first << "-" << edge.second << " repeated";
    ASSERT_EQ(directed.count({edge.second, edge.first}), 1u)
        << "edge " << edge.first << "-" << edge.second << " has no opposite";
  }
}

TEST(ProceduralMeshes, TorusOf20x20Has800Triangles) {
  const Mesh torus = makeTorus(0.5, 0.2, 20, 20);
  EXPECT_EQ(torus.triangleCount(), 800u);
  EXPECT_EQ(torus.vertices.size(), 400u);
  EXPECT_EQ(makeTorus(1.0, 0.3, 7, 5).triangleCount(), 7u * 5u * 2u);
}

TEST(ProceduralMeshes, TorusIsClosedWithOutwardWinding) {
  const double R = 0.5, r = 0.2;
  const Mesh torus = makeTorus(R, r, 20, 20);
  expectClosedAndConsistent(torus);
  // Positive volume close to 2 pi^2 R r^2 (the polygon tube is slightly thinner).
  const double exact = 2 * std::numbers::pi * std::numbers::pi * R * r * r;
  EXPECT_GT(signedVolume(torus), 0.95 * exact);
  EXPECT_LT(signedVolume(torus), exact);
  // Each face points away from the tube's centre circle.
  for (const auto& t : torus.triangles) {
    const Eigen::Vector3d c = (vertex(torus, t[0]) + vertex(torus, t[1]) + vertex(torus, t[2])) / 3;
    const Eigen::Vector3d onCircle = Eigen::Vector3d(c.x(), 0, c.z()).normalized() * R;
    ASSERT_GT(normalOf(torus, t).dot(c - onCircle), 0);
  }
}

TEST(ProceduralMeshes, TorusLiesAroundTheYAxis) {
  const Mesh torus = makeTorus(0.5, 0.2, 20, 20);
  const auto box = torus.bounds();
  EXPECT_NEAR(box.max().x(), 0.7, 1e-6);
  EXPECT_NEAR(box.min().x(), -0.7, 1e-6);
  EXPECT_NEAR(box.max().y(), 0.2, 0.01);
  EXPECT_NEAR(box.min().y(), -0.2, 0.01);
  EXPECT_NEAR(box.max().z(), 0.7, 0.01);
}

TEST(ProceduralMeshes, PlaneOf30x30Has1800TrianglesFacingUp) {
  const Mesh plane = makePlane(8.0, 30);
  EXPECT_EQ(plane.triangleCount(), 1800u);
  EXPECT_EQ(plane.vertices.size(), 31u * 31u);
  for (const auto& t : plane.triangles) {
    const Eigen::Vector3d n = normalOf(plane, t);
    ASSERT_GT(n.y(), 0);
    ASSERT_DOUBLE_EQ(n.x(), 0);
    ASSERT_DOUBLE_EQ(n.z(), 0);
  }
  const auto box = plane.bounds();
  EXPECT_EQ(box.min(), Eigen::Vector3d(-4, 0, -4));
  EXPECT_EQ(box.max(), Eigen::Vector3d(4, 0, 4));
}

TEST(ProceduralMeshes, RejectsImpossibleParameters) {
  EXPECT_THROW((void)makeTorus(0.2, 0.5, 20, 20), InputError);  // tube crosses the axis
  EXPECT_THROW((void)makeTorus(0.5, 0.2, 2, 20), InputError);
  EXPECT_THROW((void)makeTorus(0.5, 0.0, 20, 20), InputError);
  EXPECT_THROW((void)makePlane(0.0, 30), InputError);
  EXPECT_THROW((void)makePlane(1.0, 0), InputError);
}

// --- loading -------------------------------------------------------------------------------------

std::string errorOf(const std::filesystem::path& file) {
  try {
    (void)loadMesh(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no error>";
}

constexpr const char* kQuadObj =
    "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\n"
    "f 1 2 3 4\n";

TEST(MeshLoader, TriangulatesAndJoinsAcrossObjects) {
  ScratchDir dir;
  // Two objects sharing an edge, written with separate (duplicate) vertices.
  const auto file = dir.write("two.obj",
                              "o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
                              "o b\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\nf 4 5 6 7\n");
  const LoadedMesh loaded = loadMesh(file);
  EXPECT_EQ(loaded.mesh.triangleCount(), 3u);  // one triangle + a quad in two
  EXPECT_EQ(loaded.mesh.vertices.size(), 5u);  // the shared edge's vertices joined
  EXPECT_EQ(loaded.dropped.degenerateTriangles, 0u);
  EXPECT_EQ(loaded.mesh.name, "two");
}

TEST(MeshLoader, ReadsPly) {
  ScratchDir dir;
  const auto file = dir.write("tri.ply",
                              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                              "property float y\nproperty float z\nelement face 1\n"
                              "property list uchar int vertex_indices\nend_header\n"
                              "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(loadMesh(file).mesh.triangleCount(), 1u);
}

// The layout of the Stanford scans' PLY files (a comment, per-vertex confidence and intensity),
// here with CRLF line ends and a body that does not keep one item per line: the same mesh as the
// OBJ.
TEST(MeshLoader, StanfordStylePlyGivesTheSameMeshAsTheObj) {
  ScratchDir dir;
  const auto obj = dir.write("tetra.obj",
                             "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                             "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  const auto ply =
      dir.write("tetra.ply",
                "ply\r\nformat ascii 1.0\r\ncomment zipper output\r\nelement vertex 4\r\n"
                "property float x\r\nproperty float y\r\nproperty float z\r\n"
                "property float confidence\r\nproperty float intensity\r\nelement face 4\r\n"
                "property list uchar int vertex_indices\r\nend_header\r\n"
                "0 0 0 1 0.5\r\n1 0 0 1 0.5 0 1 0\r\n1 0.5\r\n0 0 1 1 0.5\r\n"
                "3 0 2 1\r\n3 0 1 3 3 0 3 2\r\n3 1 2 3\r\n");
  const Mesh fromObj = loadMesh(obj).mesh;
  const Mesh fromPly = loadMesh(ply).mesh;
  EXPECT_EQ(fromPly.vertices, fromObj.vertices);
  EXPECT_EQ(fromPly.triangles, fromObj.triangles);
  EXPECT_EQ(fromPly.triangleCount(), 4u);
}

TEST(MeshLoader, EmptyFileHasNoTriangles) {
  ScratchDir dir;
  const auto file = dir.write("empty.obj", "");
  const std::string message = errorOf(file);
  EXPECT_NE(message.find(file.string() + ": mesh has no triangles"), std::string::npos) << message;
}

TEST(MeshLoader, VerticesWithoutFacesHaveNoTriangles) {
  ScratchDir dir;
  const auto file = dir.write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  const std::string message = errorOf(file);
  EXPECT_NE(message.find(file.string() + ": mesh has no triangles"), std::string::npos) << message;
}

TEST(MeshLoader, NanAndInfiniteCoordinatesNameTheFile) {
  ScratchDir dir;
  for (const char* bad : {"nan", "inf", "-inf"}) {
    const auto file = dir.write(std::string("bad_") + bad + ".obj",
                                std::string("v 0 0 0\nv ") + bad + " 0 0\nv 0 1 0\nf 1 2 3\n");
    const std::string message = errorOf(file);
    EXPECT_EQ(message.rfind(file.string() + ": ", 0), 0u) << message;
    EXPECT_NE(message.find("expected finite coordinates"), std::string::npos) << message;
  }
}

TEST(MeshLoader, DropsAndCountsDegenerateTriangles) {
  ScratchDir dir;
  // Faces 2 (repeated vertex) and 3 (collinear: zero area) are degenerate.
  const auto file = dir.write("degenerate.obj",
                              "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\n"
                              "f 1 2 3\nf 1 1 2\nf 1 2 4\nl 1 2\n");
  testing::internal::CaptureStderr();
  const LoadedMesh loaded = loadMesh(file);
  const std::string warning = testing::internal::GetCapturedStderr();
  EXPECT_EQ(loaded.mesh.triangleCount(), 1u);
  EXPECT_EQ(loaded.dropped.degenerateTriangles, 2u);
  EXPECT_EQ(loaded.dropped.nonTriangleFaces, 1u);
  EXPECT_EQ(loaded.mesh.vertices.size(), 3u);  // vertex 4 is used by no triangle left
  EXPECT_EQ(loaded.dropped.unusedVertices, 1u);
  EXPECT_NE(warning.find("dropped 2 degenerate"), std::string::npos) << warning;
  EXPECT_NE(warning.find(file.string()), std::string::npos) << warning;
  EXPECT_EQ(std::count(warning.begin(), warning.end(), '\n'), 1) << warning;
}

TEST(MeshLoader, OnlyDegenerateTrianglesIsAnError) {
  ScratchDir dir;
  const auto file = dir.write("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  testing::internal::CaptureStderr();
  const std::string message = errorOf(file);
  (void)testing::internal::GetCapturedStderr();
  EXPECT_NE(message.find(file.string() + ": mesh has no triangles"), std::string::npos) << message;
}

TEST(MeshLoader, MissingFileGivesAssimpsReason) {
  ScratchDir dir;
  const auto file = dir.path() / "nowhere.obj";
  const std::string message = errorOf(file);
  EXPECT_EQ(message.rfind(file.string() + ": cannot load mesh: ", 0), 0u) << message;
  EXPECT_NE(message.find("Unable to open file"), std::string::npos) << message;
}

TEST(MeshLoader, UnreadableFormatGivesAssimpsReason) {
  ScratchDir dir;
  const auto file = dir.write("notes.xyzzy", "not a mesh");
  const std::string message = errorOf(file);
  EXPECT_EQ(message.rfind(file.string() + ": cannot load mesh: ", 0), 0u) << message;
  // assimp reads the bytes from memory under the file's own name: its reason names no other file.
  EXPECT_EQ(message.find("mesh.xyzzy"), std::string::npos) << message;
}

TEST(MeshLoader, NormaliseCentresAndScalesTheLongestSide) {
  ScratchDir dir;
  Mesh mesh = loadMesh(dir.write("quad.obj", kQuadObj)).mesh;  // 2 x 1 x 0 at (1, 0.5, 0)
  normaliseMesh(mesh, 3.0);
  const auto box = mesh.bounds();
  EXPECT_NEAR(box.sizes().maxCoeff(), 3.0, 1e-6);
  EXPECT_NEAR(box.sizes().y(), 1.5, 1e-6);
  EXPECT_NEAR(box.center().norm(), 0.0, 1e-6);
  EXPECT_THROW(normaliseMesh(mesh, 0.0), InputError);
}

TEST(MeshLoader, StanfordDragonHasTheThesisTriangleCount) {
  const auto file = test::findTestAsset("dragon_vrip_res3");
  if (!file) GTEST_SKIP() << "dragon_vrip_res3 not on the asset path (scripts/fetch-assets.sh)";
  LoadedMesh loaded = loadMesh(*file);
  EXPECT_EQ(loaded.mesh.triangleCount(), 47794u);
  // The file holds 22,998 vertices, 16 of which no triangle uses: they are left out (by assimp
  // already for an OBJ, by the loader for the PLY).
  EXPECT_EQ(loaded.mesh.vertices.size(), 22982u);
  EXPECT_EQ(loaded.dropped.degenerateTriangles, 0u);
  // Stored in scan coordinates, about 0.2 across and off-centre: normalisation fixes both.
  EXPECT_LT(loaded.mesh.bounds().sizes().maxCoeff(), 0.5);
  normaliseMesh(loaded.mesh, 1.5);
  const auto box = loaded.mesh.bounds();
  EXPECT_NEAR(box.sizes().maxCoeff(), 1.5, 1e-5);
  EXPECT_NEAR(box.center().norm(), 0.0, 1e-5);
}

// --- asset path ----------------------------------------------------------------------------------

TEST(AssetPath, SearchOrderIsOptionsThenEnvironmentThenRepository) {
  ScopedEnv env(kAssetsEnvVar, "/env/a::/env/b");
  const auto dirs = assetSearchPath({"/cli/1", "/cli/2"});
  const std::vector<std::string> expected{"/cli/1", "/cli/2", "/env/a", "/env/b",
                                          repositoryAssetDir().string()};
  EXPECT_EQ(dirs, expected);
  EXPECT_EQ(repositoryAssetDir(), std::filesystem::path(CDBENCH_SOURCE_DIR) / "assets");
}

TEST(AssetPath, WithoutEnvironmentOnlyOptionsAndRepository) {
  ScopedEnv env(kAssetsEnvVar, nullptr);
  const std::vector<std::string> expected{"/cli", repositoryAssetDir().string()};
  EXPECT_EQ(assetSearchPath({"/cli"}), expected);
}

TEST(AssetPath, FirstDirectoryWinsAndPlyBeforeObj) {
  ScratchDir first, second;
  second.write("shape.ply", "x");
  first.write("shape.obj", "x");
  second.write("other.obj", "x");
  second.write("other.ply", "x");
  const std::vector<std::string> dirs{first.path().string(), second.path().string()};
  EXPECT_EQ(resolveAsset("shape", dirs), first.path() / "shape.obj");
  EXPECT_EQ(resolveAsset("other", dirs), second.path() / "other.ply");
  EXPECT_EQ(resolveAsset("other.obj", dirs), second.path() / "other.obj");  // extension given
  EXPECT_EQ(resolveAsset((second.path() / "other.obj").string(), {}), second.path() / "other.obj");
}

// A run records which copy of each asset mesh it loaded: path, size and SHA-256 (FIPS 180-2's
// example digests), each asset once, and a copy found earlier on the path is another file.
TEST(AssetFiles, RecordTheFileEachAssetResolvedToWithItsSizeAndSha256) {
  ScratchDir first, second;
  second.write("shape.obj", "abc");
  ScenarioConfig config;
  BodyGroup torus, shape, again;
  torus.mesh.kind = MeshSpec::Kind::Torus;
  shape.mesh.kind = again.mesh.kind = MeshSpec::Kind::Asset;
  shape.mesh.asset = again.mesh.asset = "shape";
  config.bodies = {torus, shape, again};
  const std::vector<std::string> dirs{first.path().string(), second.path().string()};
  auto files = assetFiles(config, dirs);
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files[0].asset, "shape");
  EXPECT_EQ(files[0].path, second.path() / "shape.obj");
  EXPECT_EQ(files[0].bytes, 3u);
  EXPECT_EQ(files[0].sha256, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");

  first.write("shape.ply", "");
  files = assetFiles(config, dirs);
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files[0].path, first.path() / "shape.ply");
  EXPECT_EQ(files[0].bytes, 0u);
  EXPECT_EQ(files[0].sha256, "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  config.bodies = {torus};
  EXPECT_TRUE(assetFiles(config, dirs).empty());
}

TEST(AssetPath, MissingAssetSaysWhereItLookedAndHowToGetIt) {
  ScratchDir dir;
  const std::vector<std::string> dirs{dir.path().string(), "/no/such/dir"};
  try {
    (void)resolveAsset("dragon_vrip_res3", dirs);
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string message = e.what();
    for (const std::string& part :
         {std::string("dragon_vrip_res3.ply"), std::string("dragon_vrip_res3.obj"),
          dir.path().string(), std::string("/no/such/dir"), std::string("scripts/fetch-assets.sh"),
          std::string("--assets DIR"), std::string("CDBENCH_ASSETS")}) {
      EXPECT_NE(message.find(part), std::string::npos) << part << " missing from: " << message;
    }
    EXPECT_EQ(message.find('\n'), std::string::npos);
  }
}

}  // namespace
}  // namespace cdb
