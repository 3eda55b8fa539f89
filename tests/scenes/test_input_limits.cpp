// Limits on input that are checked outside the YAML schema: the triangle count of a mesh file, a
// swept object count its placement region cannot hold, integers too large for the command line,
// and the in-memory entry points the fuzz targets use.
#include <gtest/gtest.h>

#include <cstddef>
#include <fstream>
#include <iterator>
#include <span>
#include <string>
#include <string_view>
#include <utility>

#include "ScratchDir.h"
#include "core/Errors.h"
#include "scenes/ConfigLoader.h"
#include "scenes/MeshLoader.h"
#include "scenes/PlacementCapacity.h"
#include "scenes/PoseRecording.h"
#include "scenes/SceneBuilder.h"

namespace cdb {
namespace {

using test::ScratchDir;

template <class Fn>
std::string errorOf(Fn&& fn) {
  try {
    fn();
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no error>";
}

std::span<const std::byte> bytesOf(std::string_view s) {
  return std::as_bytes(std::span<const char>(s.data(), s.size()));
}

constexpr std::string_view kTetrahedronObj =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
    "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

TEST(MeshTriangleLimit, AtTheLimitLoads) {
  ScratchDir dir;
  const auto file = dir.write("tetra.obj", kTetrahedronObj);
  EXPECT_EQ(loadMesh(file, {4}).mesh.triangleCount(), 4u);
}

TEST(MeshTriangleLimit, AboveTheLimitNamesTheFileTheLimitAndTheCount) {
  ScratchDir dir;
  const auto file = dir.write("tetra.obj", kTetrahedronObj);
  const std::string message = errorOf([&] { (void)loadMesh(file, {3}); });
  EXPECT_EQ(message.rfind(file.string() + ": expected at most 3 triangles", 0), 0u) << message;
  EXPECT_NE(message.find("max_triangles"), std::string::npos) << message;
  EXPECT_NE(message.find("got 4"), std::string::npos) << message;
}

TEST(MeshTriangleLimit, DefaultHoldsMillionsOfTriangles) {
  EXPECT_EQ(MeshLoadOptions{}.maxTriangles, limits::kDefaultMeshTriangles);
  EXPECT_GE(limits::kDefaultMeshTriangles, 7'219'045);  // the XYZ RGB dragon
  EXPECT_LE(3 * limits::kMeshTriangles.max, (1ll << 31) - 1);
}

TEST(MeshTriangleLimit, ConfigKeySetsItAndIsChecked) {
  ScratchDir dir;
  const std::string head =
      "environment: t\nbodies:\n"
      "  - {name: a, count: 1, placement: {region_min: [0, 0, 0], region_max: [9, 9, 9]},\n"
      "     mesh: {kind: asset, asset: tetra, max_triangles: ";
  const auto config = loadScenarioConfig(dir.write("ok.yaml", head + "12}}\n"));
  EXPECT_EQ(config.bodies[0].mesh.maxTriangles, 12);
  const std::string message =
      errorOf([&] { (void)loadScenarioConfig(dir.write("bad.yaml", head + "0}}\n")); });
  EXPECT_NE(message.find("bodies[0].mesh.max_triangles: expected an integer in [1, 500000000]"),
            std::string::npos)
      << message;
  EXPECT_EQ(loadScenarioConfig(dir.write("default.yaml", head + "8000000}}\n"))
                .bodies[0]
                .mesh.maxTriangles,
            limits::kDefaultMeshTriangles);
}

TEST(MeshTriangleLimit, SceneBuilderPassesTheConfigsLimit) {
  ScratchDir dir;
  dir.write("assets/tetra.obj", kTetrahedronObj);
  const auto config = loadScenarioConfig(dir.write(
      "c.yaml",
      "environment: t\nbodies:\n"
      "  - {name: a, count: 1, placement: {region_min: [0, 0, 0], region_max: [9, 9, 9]},\n"
      "     mesh: {kind: asset, asset: tetra, max_triangles: 2}}\n"));
  const std::string message =
      errorOf([&] { (void)buildScene(config, {(dir.path() / "assets").string()}); });
  EXPECT_NE(message.find("tetra.obj: expected at most 2 triangles"), std::string::npos) << message;
}

TEST(MeshLoaderMessages, PointsAndLinesOnlySaysSo) {
  ScratchDir dir;
  const auto file = dir.write("wire.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1\nl 1 2\nl 2 3\n");
  const std::string message = errorOf([&] { (void)loadMesh(file); });
  EXPECT_EQ(message.rfind(file.string() + ": mesh has no triangles", 0), 0u) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(MeshLoaderMessages, IndexPastTheVerticesIsAnInputError) {
  ScratchDir dir;
  const auto file = dir.write("index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  const std::string message = errorOf([&] { (void)loadMesh(file); });
  EXPECT_EQ(message.rfind(file.string() + ": ", 0), 0u) << message;
}

// A mesh file is read alone: assimp 5.2's OBJ importer opens the material library a file names,
// or the file's name with .mtl, and crashes on some (fuzz/regressions/mesh/ keeps the bytes).
TEST(MeshLoaderMessages, FilesBesideTheMeshAreNotRead) {
  ScratchDir dir;
  const std::string_view crashing("\0mtllib  3\0a\0\0\0t", 16);
  dir.write("library.mtl", crashing);
  dir.write("fallback.mtl", crashing);
  const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  for (const auto& [name, text] :
       {std::pair<std::string, std::string>("named.obj", "mtllib library.mtl\n" + triangle),
        {"fallback.obj", "mtllib missing.mtl\n" + triangle},
        {"itself.obj", "mtllib itself.obj\n" + triangle + std::string(crashing)}}) {
    const auto file = dir.write(name, text);
    EXPECT_EQ(loadMesh(file).mesh.triangleCount(), 1u) << name;
  }
}

// assimp's PLY reader never returns on a header without end_header; the loader refuses it first.
TEST(MeshLoaderMessages, PlyHeaderThatNeverEndsIsRefused) {
  ScratchDir dir;
  for (std::string_view header : {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n",
                                  "ply\nformat ascii 1.0\nelem\x01", "ply",
                                  "ply\nformat ascii 1.0\nelement vertex 3 end_header\n",
                                  "ply\nformat ascii 1.0\nelement vertex 3\nend_headerX\n",
                                  "ply\nformat ascii 1.0\nend_header\v\n"}) {
    const auto file = dir.write("cut.ply", header);
    const std::string message = errorOf([&] { (void)loadMesh(file); });
    EXPECT_EQ(message.rfind(
                  file.string() + ": expected a PLY header that ends with a line end_header", 0),
              0u)
        << message;
    EXPECT_NE(errorOf([&] {
                (void)loadMeshFromMemory(bytesOf(header), "ply", "m.ply");
              }).find("end_header"),
              std::string::npos);
  }
  // A carriage return that does not end a line stalls assimp's header reader just the same.
  const auto cr = dir.write("cr.ply", "ply\nformat ascii 1.0\nelement vertex 3\n\rend_header\n0\n");
  EXPECT_NE(
      errorOf([&] { (void)loadMesh(cr); }).find("PLY header line 4: expected lines ending in LF"),
      std::string::npos)
      << errorOf([&] { (void)loadMesh(cr); });
  // Content decides too: a PLY under another extension is read as one by assimp.
  const auto renamed = dir.write("cut.mesh", "ply\nformat ascii 1.0\n");
  EXPECT_NE(errorOf([&] { (void)loadMesh(renamed); }).find("end_header"), std::string::npos);
  // The header's end as assimp reads it: own line, blanks before, whitespace or the end after.
  for (std::string_view header : {"ply\nformat ascii 1.0\n  end_header \n", "ply\r\nend_header\r\n",
                                  "ply\nformat ascii 1.0\nend_header"}) {
    EXPECT_EQ(errorOf([&] {
                (void)loadMeshFromMemory(bytesOf(header), "ply", "m.ply");
              }).find("end_header"),
              std::string::npos)
        << header;
  }
  // An OBJ that mentions ply is not a PLY.
  const auto obj = dir.write("ply.obj", "# ply\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_EQ(loadMesh(obj).mesh.triangleCount(), 1u);
}

TEST(MeshFromMemory, ReadsObjAndPlyLikeTheFileLoader) {
  const LoadedMesh obj = loadMeshFromMemory(bytesOf(kTetrahedronObj), "obj", "mem.obj");
  EXPECT_EQ(obj.mesh.triangleCount(), 4u);
  EXPECT_EQ(obj.mesh.vertices.size(), 4u);
  EXPECT_EQ(obj.mesh.name, "mem");
  constexpr std::string_view ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_EQ(loadMeshFromMemory(bytesOf(ply), "ply", "mem.ply").mesh.triangleCount(), 1u);
}

// assimp's own memory file system hands a material library the mesh's bytes, and its OBJ importer
// crashes on them; from memory there is no other file (scenes/InMemoryMeshFile.h).
TEST(MeshFromMemory, MaterialLibrariesAreIgnored) {
  constexpr std::string_view obj =
      "mtllib  5 -1\n  mtllib x.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  EXPECT_EQ(loadMeshFromMemory(bytesOf(obj), "obj", "m.obj").mesh.triangleCount(), 1u);
  // assimp ends an OBJ line also at CR, form feed and NUL, and at a library that names the mesh
  // itself or its fallback, the mesh's name with .mtl (fuzz/regressions/mesh/ keeps the input
  // that crashed with a statement after a NUL).
  for (const std::string_view library :
       {std::string_view("\rmtllib x.mtl\n"), std::string_view("\fmtllib x.mtl\n"),
        std::string_view("\0mtllib x.mtl\n", 15), std::string_view("\0mtllib  3\0a\0\0\0t", 16),
        std::string_view("\nmtllib mesh.obj\n"), std::string_view("\nmtllib m.obj\n"),
        std::string_view("\nmtllib mesh.mtl\n"), std::string_view("\nmtllib mesh\n")}) {
    const std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3" + std::string(library);
    EXPECT_EQ(loadMeshFromMemory(bytesOf(text), "obj", "m.obj").mesh.triangleCount(), 1u)
        << library;
    EXPECT_EQ(loadMeshFromMemory(bytesOf(text), "", "m").mesh.triangleCount(), 1u) << library;
    // A name assimp would split a folder off is not given to it.
    EXPECT_EQ(loadMeshFromMemory(bytesOf(text), "obj", "dir\\m.obj").mesh.triangleCount(), 1u)
        << library;
  }
}

TEST(MeshFromMemory, BadBytesAreInputErrorsNamingTheMesh) {
  for (std::string_view bad :
       {std::string_view(), std::string_view("v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
        std::string_view("ply\nformat binary_little_endian 1.0\n"),
        std::string_view("\x00\x01\x02garbage", 10)}) {
    const std::string message =
        errorOf([&] { (void)loadMeshFromMemory(bytesOf(bad), "obj", "x.obj"); });
    EXPECT_EQ(message.rfind("x.obj: ", 0), 0u) << message;
  }
}

TEST(ObjectCountCapacity, ASweptCountTheRegionCannotHoldIsInput) {
  ScratchDir dir;
  const auto config = loadScenarioConfig(
      dir.write("c.yaml",
                "environment: t\nbodies:\n"
                "  - {name: tori, mesh: {kind: torus}, count: 3,\n"
                "     placement: {region_min: [-2, -2, -2], region_max: [2, 2, 2]}}\n"
                "sweep: {counted_group: tori, object_counts: [3]}\n"));
  EXPECT_EQ(withObjectCount(config, 10).bodies[0].count, 10);
  const std::string message = errorOf([&] { (void)withObjectCount(config, 5000); });
  EXPECT_EQ(message.rfind(config.sourcePath + ": object count 5000 of 'tori': expected", 0), 0u)
      << message;
  EXPECT_NE(message.find("at most 30%"), std::string::npos) << message;
}

TEST(ObjectCountCapacity, FillGrowsWithTheCount) {
  BodyGroup body;
  body.placement = RandomPlacement{};
  body.placement->regionMin = {-1, -1, -1};
  body.placement->regionMax = {1, 1, 1};
  EXPECT_DOUBLE_EQ(placementFill(body, 20), 2 * placementFill(body, 10));
  EXPECT_DOUBLE_EQ(boundingRadius(body.mesh), body.mesh.majorRadius + body.mesh.minorRadius);
}

TEST(IntListRange, IntegerBeyondIntSaysTheRange) {
  const std::string message = errorOf([] { (void)parseIntList("99999999999"); });
  EXPECT_EQ(message,
            "'99999999999': expected an integer in [-2147483648, 2147483647], got "
            "'99999999999'");
  EXPECT_NE(errorOf([] { (void)parseIntList("12x"); }).find("expected an integer, got '12x'"),
            std::string::npos);
}

TEST(ConfigFromText, NamesTheGivenNameInMessages) {
  const auto config = loadScenarioConfigFromText(
      "environment: t\nbodies:\n"
      "  - {name: a, mesh: {kind: torus}, count: 1,\n"
      "     placement: {region_min: [0, 0, 0], region_max: [9, 9, 9]}}\n",
      "memory.yaml");
  EXPECT_EQ(config.sourcePath, "memory.yaml");
  const std::string message =
      errorOf([] { (void)loadScenarioConfigFromText("environment: [", "memory.yaml"); });
  EXPECT_EQ(message.rfind("memory.yaml:", 0), 0u) << message;
}

TEST(RecordingFromBytes, ReadsWhatWasWrittenAndNamesTheSourceInErrors) {
  ScratchDir dir;
  PoseRecording recording;
  recording.environment = "t";
  recording.objectCount = 2;
  recording.poses.resize(6);
  recording.poses[3].translation = {1, 2, 3};
  const auto file = dir.path() / "r.poses";
  writePoseRecording(recording, file);
  std::ifstream in(file, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const PoseRecording back = readPoseRecordingFromBytes(bytes, "mem.poses");
  EXPECT_EQ(back.frameCount(), 3u);
  EXPECT_EQ(back.hash(), recording.hash());
  const std::string message = errorOf([&] {
    (void)readPoseRecordingFromBytes(std::span(bytes).first(bytes.size() - 1), "mem.poses");
  });
  EXPECT_EQ(message.rfind("mem.poses: truncated", 0), 0u) << message;
}

// Poses the simulation never records are refused when read back, naming frame and object.
TEST(RecordingFromBytes, RefusesNonUnitRotationsAndFarPositions) {
  ScratchDir dir;
  const auto messageFor = [&](const Pose& bad) {
    PoseRecording recording;
    recording.environment = "t";
    recording.objectCount = 2;
    recording.poses.resize(4);
    recording.poses[3] = bad;
    const auto file = dir.path() / "bad.poses";
    writePoseRecording(recording, file);
    return errorOf([&] { (void)readPoseRecording(file); });
  };
  Pose zero;
  zero.rotation = Eigen::Quaterniond(0, 0, 0, 0);
  EXPECT_NE(messageFor(zero).find("frame 1 object 1: expected a unit quaternion"),
            std::string::npos)
      << messageFor(zero);
  Pose far;
  far.translation = {1e300, 0, 0};
  EXPECT_NE(messageFor(far).find("frame 1 object 1: expected a position within"), std::string::npos)
      << messageFor(far);
}

}  // namespace
}  // namespace cdb
