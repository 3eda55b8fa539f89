#include "culling/visibility/cpu/CpuPieces.h"

#include <algorithm>

#include "culling/visibility/cpu/CpuChunkLanes.h"
#include "culling/visibility/cpu/CpuPassSpace.h"

namespace cdb {

namespace {

// The unit cube [-1, 1]^3 (corner i has x, y, z = bits 0, 1, 2) as two triangles per face;
// faces in the order -x, +x, -y, +y, -z, +z. A face's two triangles share their first and third
// corner, so a, b, c of the first and the second's last go around the face.
constexpr std::array<std::array<int, 6>, 6> kCubeFaces = {{{0, 2, 6, 0, 6, 4},
                                                           {1, 5, 7, 1, 7, 3},
                                                           {0, 4, 5, 0, 5, 1},
                                                           {2, 3, 7, 2, 7, 6},
                                                           {0, 1, 3, 0, 3, 2},
                                                           {4, 6, 7, 4, 7, 5}}};

// The faces of a box that decide its answer (in kCubeFaces order). A box is convex: along any
// line of sight the faces facing away from the viewer are farthest and those facing it nearest,
// and each set covers the box's whole outline. So in every pixel the farthest depth of the box
// over the part of the square it covers is reached on a back face (what a test needs), the nearest
// on a front face (a write): the other faces change nothing. Faces seen edge-on (key not changing
// along their normal) belong to both sets.
// (A mask, bit f for face f: an array of flags made here was read back through the stack as one
// word, a store-forwarding stall on a fifth of boxPieces' time.)
unsigned decidingFaces(const ScreenMatrix& cube, CpuCommand::Role role) {
  unsigned keep = 0;
  const bool test = role == CpuCommand::Role::Test;
  for (int axis = 0; axis < 3; ++axis) {
    const double outward = cube(2, axis);  // how the key changes going out through the + face
    for (int positive = 0; positive < 2; ++positive) {
      const double away = positive ? outward : -outward;  // > 0: the face looks away (back)
      if (away == 0.0 || (test ? away > 0.0 : away < 0.0)) keep |= 1u << (2 * axis + positive);
    }
  }
  return keep;
}

}  // namespace

void chunkPieces(const CpuRun& run, const CpuMeshBounds& bounds, const CpuCommand& c,
                 const CpuItem& item, const PixelRect& window, double marginPx, bool everyCorner,
                 CpuPieces& out) {
  out.areQuads = false;
  out.hasExtents = true;
  out.count = 0;
  const bool listed = c.source == CpuCommand::Source::Listed;
  // A pixel box lies within [minX - margin - 1, maxX + margin] (and the same in y), in either
  // rasterisation mode (setupBounds: from ceil(minX - margin) - 1 to floor(maxX + margin); raw
  // mode's centre rule lies within), so it meets the window only if maxX >= x0 - margin and
  // minX <= x1 + margin + 1; half a pixel more is left for rounding.
  const double below = marginPx + 0.5, above = marginPx + 1.5;
  const double wx0 = window.x0 - below, wx1 = window.x1 + above;
  const double wy0 = window.y0 - below, wy1 = window.y1 + above;
  const CpuItemParts& partRects = run.bins.parts[item.parts];
  const std::uint32_t count = item.count;
  unsigned parts = 0;
  for (std::uint32_t part = 0; part < count; part += kPartTriangles)
    if (partRects[part / kPartTriangles].overlaps(window)) parts |= 1u << (part / kPartTriangles);
  const ChunkGather how{
      {wx0, wx1, wy0, wy1}, c.winding, c.role == CpuCommand::Role::Test, marginPx, everyCorner};
  constexpr std::size_t kChunkRows = std::size_t{kChunkCornerRows} * kChunkTriangles;
  if (!listed && item.first % kChunkTriangles == 0) {  // a mesh chunk's own rows
    gatherChunkInLanes(bounds.chunkCorners.data() + item.first / kChunkTriangles * kChunkRows,
                       count, parts, c.toScreen, how, out);
    return;
  }
  // Other triangles (a list's, or a Range off the chunk grid) copied into rows of their own, those
  // of the parts that meet the window; a SIMD step past the item's last triangle repeats it.
  alignas(64) float rows[kChunkRows];
  const auto triangleAt = [&](std::uint32_t i) {
    return listed ? run.recording.listed[item.first + i] : item.first + i;
  };
  for (std::uint32_t part = 0; part < count; part += kPartTriangles) {
    if ((parts >> (part / kPartTriangles) & 1u) == 0) continue;
    const std::uint32_t end = std::min(count, part + kPartTriangles);
    const std::uint32_t filled = std::min(part + kPartTriangles, (end + 7) / 8 * 8);
    for (std::uint32_t i = part; i < filled; ++i) {
      const std::uint32_t tri = triangleAt(std::min(i, end - 1));
      const float* from =
          bounds.chunkCorners.data() + tri / kChunkTriangles * kChunkRows + tri % kChunkTriangles;
      for (std::uint32_t r = 0; r < kChunkCornerRows; ++r)
        rows[r * kChunkTriangles + i] = from[r * kChunkTriangles];
    }
  }
  gatherChunkInLanes(rows, count, parts, c.toScreen, how, out);
}

ScreenMatrix cubeToScreen(const ScreenMatrix& objectToScreen, const OrientedBox& box) {
  ScreenMatrix m;
  m.leftCols<3>() = objectToScreen.leftCols<3>() * box.axes * box.halfExtents.asDiagonal();
  m.col(3) = objectToScreen.leftCols<3>() * box.center + objectToScreen.col(3);
  return m;
}

void boxPieces(const ScreenMatrix& cube, CpuCommand::Role role, bool conservative, CpuPieces& out) {
  // The corners, bit for bit screenPoint(cube, +-1, +-1, +-1) (corner i: x, y, z = bits 0, 1, 2):
  // a product by +-1 is exact, so each of its sums is formed from the signed columns in its order,
  // shared between the corners that have it.
  std::array<Eigen::Vector3d, 8> corner;
  for (int row = 0; row < 2; ++row) {  // x, y: ((m0 x + m1 y) + m2 z) + m3
    const double m0 = cube(row, 0), m1 = cube(row, 1), m2 = cube(row, 2), m3 = cube(row, 3);
    const double xy[4] = {-m0 + -m1, m0 + -m1, -m0 + m1, m0 + m1};
    for (int i = 0; i < 8; ++i) corner[i][row] = (xy[i & 3] + ((i & 4) ? m2 : -m2)) + m3;
  }
  {  // key: (m0 x + (m1 y + m2 z)) + m3
    const double m0 = cube(2, 0), m1 = cube(2, 1), m2 = cube(2, 2), m3 = cube(2, 3);
    const double yz[4] = {-m1 + -m2, m1 + -m2, -m1 + m2, m1 + m2};
    for (int i = 0; i < 8; ++i) corner[i][2] = (((i & 1) ? m0 : -m0) + yz[i >> 1]) + m3;
  }
  const unsigned keep = decidingFaces(cube, role);
  out.areQuads = conservative;
  out.hasExtents = false;
  std::size_t n = 0;
  for (int f = 0; f < 6; ++f) {
    if ((keep >> f & 1u) == 0) continue;
    const auto& face = kCubeFaces[f];
    if (conservative) {
      const int around[4] = {face[0], face[1], face[2], face[5]};
      for (int v = 0; v < 4; ++v) {
        const Eigen::Vector3d& p = corner[around[v]];
        out.quads[n].x[v] = p.x(), out.quads[n].y[v] = p.y(), out.quads[n].k[v] = p.z();
      }
      ++n;
      continue;
    }
    for (int t = 0; t < 2; ++t, ++n)
      for (int v = 0; v < 3; ++v) {
        const Eigen::Vector3d& p = corner[face[3 * t + v]];
        out.triangles[n].x[v] = p.x(), out.triangles[n].y[v] = p.y(), out.triangles[n].k[v] = p.z();
      }
  }
  out.count = n;
}

}  // namespace cdb
