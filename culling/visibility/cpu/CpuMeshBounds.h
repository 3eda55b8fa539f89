#pragma once
// What binning needs to know of each mesh of the attached scene without touching its triangles:
// a box per chunk of consecutive triangles and one per triangle (in the mesh's own frame), and
// whether it is closed with a consistent winding (see CpuCommand::winding).
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

#include "scenes/SceneGeometry.h"

namespace cdb {

// Triangles of a command are binned, and rasterised in one go, in chunks of this many: small
// enough that a chunk's box is much tighter than its mesh's (a torus' 800 triangles make 13 chunks
// whose boxes are bands around its tube), large enough that binning costs little beside them.
inline constexpr std::uint32_t kChunkTriangles = 64;
static_assert(3 * kChunkTriangles <= 256, "a chunk's vertices are numbered in a byte");
// A chunk drawn in a tile is first sorted out by parts of this many triangles: a part whose box
// misses the tile costs no transform.
inline constexpr std::uint32_t kPartTriangles = 16;
static_assert(kChunkTriangles % kPartTriangles == 0);

struct CpuMeshBounds {
  std::int8_t winding = 0;
  std::vector<Eigen::AlignedBox3f> chunks;     // chunk c: triangles [c, c + 1) * kChunkTriangles
  std::vector<Eigen::AlignedBox3f> parts;      // part p: triangles [p, p + 1) * kPartTriangles
  std::vector<Eigen::AlignedBox3f> triangles;  // per triangle
  // The vertices of chunk c, each once (a vertex is shared by about six triangles, so a chunk is
  // drawn with a third as many transforms): chunkVertices[chunkVertexStart[c] ...
  // chunkVertexStart[c + 1]), and per triangle its corners among its chunk's vertices.
  std::vector<std::uint32_t> chunkVertexStart;
  std::vector<std::uint32_t> chunkVertices;
  std::vector<std::array<std::uint8_t, 3>> cornersInChunk;
};

[[nodiscard]] std::vector<CpuMeshBounds> meshBoundsOf(const SceneGeometry& scene);

}  // namespace cdb
