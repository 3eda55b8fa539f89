#pragma once
// What the backend keeps of each mesh of the attached scene: the order it draws its triangles in,
// a box per part of that order and per triangle (in the mesh's own frame; binning bounds items by
// them without touching a triangle), the triangles' corners in rows for the gather in SIMD lanes,
// and whether it is closed with a consistent winding (CpuCommand::winding).
// The order of a command's triangles changes no answer, so a mesh is drawn along a Morton curve
// through their centroids where that makes its chunks more compact than its own order: a chunk is
// then a patch of the surface, not a strip across it, and its rectangle and depth range are small.
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "scenes/SceneGeometry.h"

namespace cdb {

// Triangles of a command are binned, and rasterised in one go, in chunks of this many: small
// enough that a chunk's box is much tighter than its mesh's, large enough that binning costs
// little beside them.
inline constexpr std::uint32_t kChunkTriangles = 64;
static_assert(kChunkTriangles <= 256, "a triangle's offset in its chunk is a byte (CpuPieces)");
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
  // Each triangle's corners, chunk by chunk (chunk c: positions [c, c + 1) * kChunkTriangles) in
  // rows a SIMD step reads without following an index (CpuChunkLanes): chunk c's rows start at
  // c * kChunkCornerRows * kChunkTriangles, and row 3 v + a holds coordinate a of corner v of its
  // kChunkTriangles positions (those past the mesh's last triangle repeat it).
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
