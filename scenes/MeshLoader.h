#pragma once
// Triangle meshes from files: anything assimp reads (the project uses .ply and .obj), merged into
// one Mesh, checked, and normalised to a chosen size.
#include <cstddef>
#include <filesystem>

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

// Reads `file`, triangulates, merges every mesh of the file (with its node transform) into one,
// joins vertices at identical positions and drops vertices no triangle uses. Degenerate triangles
// are dropped with one warning line on stderr. Throws InputError naming the file when assimp cannot
// read it, when a coordinate is NaN or infinite, or when no triangle is left.
[[nodiscard]] LoadedMesh loadMesh(const std::filesystem::path& file);

// Moves the bounding-box centre to the origin and scales uniformly so that the longest side of
// the bounding box is `longestSide`. Throws InputError for an empty or flat-to-a-point mesh.
void normaliseMesh(Mesh& mesh, double longestSide);

}  // namespace cdb
