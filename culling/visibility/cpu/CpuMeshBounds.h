#pragma once
// What binning needs to know of each mesh of the attached scene without touching its triangles:
// the order the backend draws its triangles in, a box per part of that order and per triangle (in
// the mesh's own frame), and whether it is closed with a consistent winding (CpuCommand::winding).
// The order of a command's triangles changes no answer, so a mesh is drawn along a Morton curve
// through their centroids where that makes its chunks more compact than its own order: a chunk is
// then a patch of the surface, not a strip across it, and its rectangle and depth range are small.
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

#include "scenes/SceneGeometry.h"

namespace cdb {

// Triangles of a command are binned, and rasterised in one go, in chunks of this many: small
// enough that a chunk's box is much tighter than its mesh's, large enough that binning costs
// little beside them.
inline constexpr std::uint32_t kChunkTriangles = 64;
static_assert(3 * kChunkTriangles <= 256, "a chunk's vertices are numbered in a byte");
// A chunk drawn in a tile is first sorted out by parts of this many triangles: a part whose box
// misses the tile costs no transform.
inline constexpr std::uint32_t kPartTriangles = 16;
static_assert(kChunkTriangles % kPartTriangles == 0);

// Everything but `order` and `position` is indexed by position in the draw order.
struct CpuMeshBounds {
  std::int8_t winding = 0;
  std::vector<std::uint32_t> order;            // position -> mesh triangle
  std::vector<std::uint32_t> position;         // mesh triangle -> position
  std::vector<Eigen::AlignedBox3f> parts;      // part p: positions [p, p + 1) * kPartTriangles
  std::vector<Eigen::AlignedBox3f> triangles;  // per position
  // The vertices of chunk c (positions [c, c + 1) * kChunkTriangles), each once (a vertex is shared
  // by about six triangles, so a chunk is drawn with a fraction as many transforms):
  // chunkVertices[chunkVertexStart[c] ... chunkVertexStart[c + 1]), and per position its triangle's
  // corners among its chunk's vertices.
  std::vector<std::uint32_t> chunkVertexStart;  // one more than there are chunks
  std::vector<std::uint32_t> chunkVertices;
  // The mesh's vertex of each entry of chunkVertices (a copy in that layout: a chunk's vertices
  // are then read in a row when transformed, not gathered from all over the mesh).
  std::vector<Eigen::Vector3f> chunkPositions;
  std::vector<std::array<std::uint8_t, 3>> cornersInChunk;
  // The corners again, triangle by triangle, in rows a SIMD step reads without following an index
  // (CpuChunkLanes): chunk c's rows start at c * kChunkCornerRows * kChunkTriangles, and row
  // 3 v + a holds coordinate a of corner v of its kChunkTriangles positions (those past the mesh's
  // last triangle repeat it).
  std::vector<float> chunkCorners;
};
inline constexpr std::uint32_t kChunkCornerRows = 9;

[[nodiscard]] std::vector<CpuMeshBounds> meshBoundsOf(const SceneGeometry& scene);

// The draw order of `mesh`'s triangles: by the Morton code of their centroids in the mesh's
// bounding cube (10 bits an axis; non-finite centroids first), ties by triangle index.
[[nodiscard]] std::vector<std::uint32_t> drawOrderOf(const Mesh& mesh);
// The order the backend draws `mesh` in: drawOrderOf's, or the mesh's own where its chunks are at
// least as compact.
[[nodiscard]] std::vector<std::uint32_t> chosenDrawOrder(const Mesh& mesh);

}  // namespace cdb
