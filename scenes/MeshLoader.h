#pragma once
// Triangle meshes from files: anything assimp reads (the project uses .ply and .obj), merged into
// one Mesh, checked, and normalised to a chosen size.
#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

#include "scenes/ConfigLimits.h"
#include "scenes/Mesh.h"

namespace cdb {

// What loadMesh left out because it cannot take part in collision detection.
struct DroppedGeometry {
  std::size_t degenerateTriangles = 0;  // a repeated vertex or exactly zero area
  std::size_t nonTriangleFaces = 0;     // points and lines left after triangulation
  std::size_t unusedVertices = 0;       // vertices no (kept) triangle refers to
};

struct LoadedMesh {
  Mesh mesh;
  DroppedGeometry dropped;
};

struct MeshLoadOptions {
  // A file with more triangles is refused before they are merged (mesh.max_triangles).
  long long maxTriangles = limits::kDefaultMeshTriangles;
};

// Reads `file` (and nothing beside it: a material library it names is not read), triangulates,
// merges every mesh of the file (with its node transform) into one, joins vertices at identical
// positions and drops vertices no triangle uses. Degenerate triangles are dropped with one warning
// line on stderr. Throws InputError naming the file when assimp cannot read it, when a coordinate
// is NaN or infinite, when it has more than options.maxTriangles triangles, or when no triangle is
// left.
[[nodiscard]] LoadedMesh loadMesh(const std::filesystem::path& file,
                                  const MeshLoadOptions& options = {});

// The same from bytes already in memory; `formatHint` is the file extension without the dot
// ("ply", "obj") and `name` names the mesh in messages.
[[nodiscard]] LoadedMesh loadMeshFromMemory(std::span<const std::byte> bytes,
                                            std::string_view formatHint, const std::string& name,
                                            const MeshLoadOptions& options = {});

// Moves the bounding-box centre to the origin and scales uniformly so that the longest side of
// the bounding box is `longestSide`. Throws InputError for an empty or flat-to-a-point mesh.
void normaliseMesh(Mesh& mesh, double longestSide);

}  // namespace cdb
