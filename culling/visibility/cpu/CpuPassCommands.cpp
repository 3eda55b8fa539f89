#include "culling/visibility/cpu/CpuPassCommands.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>

namespace cdb {

namespace {

// Triangles go to the rasteriser in chunks: the transform loop stays simple and the dispatch
// cost is shared.
constexpr std::size_t kChunk = 64;

inline void toScreen(const ScreenMatrix& m, const Eigen::Vector3f& v, ScreenTriangle& t, int i) {
  const Eigen::Vector3d p = m.leftCols<3>() * v.cast<double>() + m.col(3);
  t.x[i] = p.x(), t.y[i] = p.y(), t.k[i] = p.z();
}

// The unit cube [-1, 1]^3 (corner i has x, y, z = bits 0, 1, 2) as two triangles per face;
// faces in the order -x, +x, -y, +y, -z, +z.
constexpr std::array<std::array<int, 6>, 6> kCubeFaces = {{
    {0, 2, 6, 0, 6, 4}, {1, 5, 7, 1, 7, 3}, {0, 4, 5, 0, 5, 1},
    {2, 3, 7, 2, 7, 6}, {0, 1, 3, 0, 3, 2}, {4, 6, 7, 4, 7, 5}}};

// Which faces of a box decide its answer (in kCubeFaces order); the reason is below.
std::array<bool, 6> decidingFaces(const ScreenMatrix& cubeToScreen, CpuCommand::Role role) {
  std::array<bool, 6> keep{};
  const bool test = role == CpuCommand::Role::Test;
  for (int axis = 0; axis < 3; ++axis) {
    // How the key changes going out through the + face of this axis.
    const double outward = cubeToScreen(2, axis);
    for (int positive = 0; positive < 2; ++positive) {
      const double away = positive ? outward : -outward;  // > 0: the face looks away (back)
      keep[2 * axis + positive] = away == 0.0 || (test ? away > 0.0 : away < 0.0);
    }
  }
  return keep;
}

// A box's corners on screen (corner i has x, y, z = bits 0, 1, 2 of the unit cube).
using BoxCorners = std::array<Eigen::Vector3d, 8>;
BoxCorners cubeCorners(const ScreenMatrix& cubeToScreen) {
  BoxCorners corner;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d c((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0);
    corner[i] = cubeToScreen.leftCols<3>() * c + cubeToScreen.col(3);
  }
  return corner;
}

// The deciding faces of a box as quads (conservative passes): each face's two triangles in
// kCubeFaces share their first and third corner, so a, b, c of the first and the second's last
// go around the face.
std::size_t boxQuads(const ScreenMatrix& cubeToScreen, const BoxCorners& corner,
                     CpuCommand::Role role, ScreenQuad* out) {
  const std::array<bool, 6> keep = decidingFaces(cubeToScreen, role);
  std::size_t n = 0;
  for (int f = 0; f < 6; ++f) {
    if (!keep[f]) continue;
    const auto& face = kCubeFaces[f];
    const int around[4] = {face[0], face[1], face[2], face[5]};
    for (int v = 0; v < 4; ++v) {
      const Eigen::Vector3d& p = corner[around[v]];
      out[n].x[v] = p.x(), out[n].y[v] = p.y(), out[n].k[v] = p.z();
    }
    ++n;
  }
  return n;
}

// The triangles of a box that decide its answer. A box is convex: along any line of sight the
// faces facing away from the viewer are farthest and those facing it nearest, and each set covers
// the box's whole outline. So in every pixel the farthest depth of the box over the part of the
// square it covers is reached on a back face (what a test needs), the nearest on a front face (a
// write): the other faces change nothing. Faces seen edge-on (key not changing along their
// normal) belong to both sets.
std::size_t boxTriangles(const ScreenMatrix& cubeToScreen, const BoxCorners& corner,
                         CpuCommand::Role role, ScreenTriangle* out) {
  const std::array<bool, 6> keep = decidingFaces(cubeToScreen, role);
  std::size_t n = 0;
  for (int f = 0; f < 6; ++f) {
    if (!keep[f]) continue;
    const auto& face = kCubeFaces[f];
    for (int t = 0; t < 2; ++t, ++n)
      for (int v = 0; v < 3; ++v) {
        const Eigen::Vector3d& p = corner[face[3 * t + v]];
        out[n].x[v] = p.x(), out[n].y[v] = p.y(), out[n].k[v] = p.z();
      }
  }
  return n;
}

// Whether a triangle of a closed mesh can decide its command. Along every line of sight a closed
// surface is crossed as often toward the viewer as away from it (its winding number is 0 far
// away), so behind each crossing of a face turned toward the viewer lies one of a face turned away,
// at the same screen point: in every pixel square, the farthest depth of the mesh over what it
// covers is reached on a face turned away (what a test needs) and the nearest on one turned
// toward the viewer (a write). Faces near edge-on (or collapsed) are kept for both. The screen
// frame (x, y, key) is right-handed, so a counter-clockwise triangle in x, y faces along +key.
inline bool drawnForRole(const ScreenTriangle& t, std::int8_t winding, CpuCommand::Role role) {
  if (winding == 0) return true;
  const double e1x = t.x[1] - t.x[0], e1y = t.y[1] - t.y[0];
  const double e2x = t.x[2] - t.x[0], e2y = t.y[2] - t.y[0];
  const double facing = winding * (e1x * e2y - e1y * e2x);  // > 0: turned away from the viewer
  // Far above double's rounding of the screen coordinates (2^-50 relative).
  const double edgeOn = 1e-9 * (std::abs(e1x) + std::abs(e1y)) * (std::abs(e2x) + std::abs(e2y));
  return role == CpuCommand::Role::Test ? facing >= -edgeOn : facing <= edgeOn;
}

// Screen triangles of the command's mesh triangles [done, done + kChunk) that it draws; returns
// how many, and advances `done` past those read.
std::size_t fillChunk(const CpuCommandList& list, const CpuCommand& c, std::uint32_t& done,
                      std::array<ScreenTriangle, kChunk>& chunk) {
  const Mesh& mesh = *c.mesh;
  const std::uint32_t n = std::min<std::uint32_t>(kChunk, c.count - done);
  std::size_t kept = 0;
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t tri = c.source == CpuCommand::Source::Range
                                  ? c.first + done + i
                                  : list.listed[c.first + done + i];
    const Triangle& t = mesh.triangles[tri];
    for (int v = 0; v < 3; ++v) toScreen(c.toScreen, mesh.vertices[t[v]], chunk[kept], v);
    if (drawnForRole(chunk[kept], c.winding, c.role)) ++kept;
  }
  done += n;
  return kept;
}

// Where a piece can reach on screen: x, y and key ranges holding all of its vertices.
struct ScreenExtent {
  double minX = raster_detail::kInf, minY = raster_detail::kInf, minK = raster_detail::kInf;
  double maxX = -raster_detail::kInf, maxY = -raster_detail::kInf, maxK = -raster_detail::kInf;
  void add(double x, double y, double k) {
    minX = std::min(minX, x), maxX = std::max(maxX, x);
    minY = std::min(minY, y), maxY = std::max(maxY, y);
    minK = std::min(minK, k), maxK = std::max(maxK, k);
  }
};

// A piece decided by the tiles under it before any of its triangles is set up: its screen extent
// gives a pixel box holding every pixel box its triangles get from setupBounds, and key bounds
// beyond all of theirs. A test whose farthest key is nearer than everything stored there is fully
// visible; a write whose nearest is at or behind everything stored changes nothing. Both are what
// drawing its triangles one by one would find (each triangle is decided by the same tiles), only
// sooner.
bool decidedByExtent(CpuDepthBuffer& buffer, const RasterPass& pass, const ScreenExtent& e,
                     CpuCommand::Role role) {
  if (!std::isfinite(e.minX + e.maxX + e.minY + e.maxY + e.minK + e.maxK)) return false;
  // A pixel more on each side and keys widened far beyond the rounding of the transforms (the
  // triangles' vertices may go through the same matrix, each rounded a little differently).
  const double m = pass.marginPx + 1.0;
  const int x0 = static_cast<int>(std::max(0.0, std::floor(e.minX - m) - 1.0));
  const int y0 = static_cast<int>(std::max(0.0, std::floor(e.minY - m) - 1.0));
  const double last = pass.resolution - 1;
  const double fx1 = std::min(last, std::ceil(e.maxX + m));
  const double fy1 = std::min(last, std::ceil(e.maxY + m));
  if (fx1 < x0 || fy1 < y0) return true;  // off-screen: no triangle of it has a pixel
  const int x1 = static_cast<int>(fx1), y1 = static_cast<int>(fy1);
  const double slack = 1e-9 * (1.0 + std::abs(e.minK) + std::abs(e.maxK));
  const bool test = role == CpuCommand::Role::Test;
  const double shift = pass.conservative ? (test ? pass.depthEpsilon : -pass.depthEpsilon)
                                         : (test ? pass.rawTestOffset : 0.0);
  const auto clampToPass = [&](float v) { return std::clamp(v, pass.keyLo, pass.keyHi); };
  const float zHi = clampToPass(raster_detail::roundUp(e.maxK + shift + slack));
  const float zLo = clampToPass(raster_detail::roundDown(e.minK + shift - slack));
  constexpr int kTile = CpuDepthBuffer::kTile;
  for (int ty = y0 / kTile; ty <= y1 / kTile; ++ty)
    for (int tx = x0 / kTile; tx <= x1 / kTile; ++tx) {
      const std::size_t index = buffer.tileIndex(tx, ty);
      const float lo = buffer.tileMin(index), hi = buffer.tileMax(index);
      const float nearest = pass.sign > 0 ? lo : -hi, farthest = pass.sign > 0 ? hi : -lo;
      if (test ? zHi >= nearest : zLo < farthest) return false;
    }
  return true;
}

// The same for a mesh given by its box in its own frame, through its matrix: the extent of the
// box's corners.
bool decidedByBounds(CpuDepthBuffer& buffer, const RasterPass& pass, const ScreenMatrix& toScreen,
                     const Eigen::AlignedBox3d& box, CpuCommand::Role role) {
  if (box.isEmpty()) return false;
  ScreenExtent e;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d corner = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i));
    const Eigen::Vector3d p = toScreen.leftCols<3>() * corner + toScreen.col(3);
    e.add(p.x(), p.y(), p.z());
  }
  return decidedByExtent(buffer, pass, e, role);
}

// The same for a box command's box, given its corners on screen (those its faces are drawn
// from: one transform of each corner serves both).
bool decidedByCorners(CpuDepthBuffer& buffer, const RasterPass& pass, const BoxCorners& corners,
                      CpuCommand::Role role) {
  ScreenExtent e;
  for (const Eigen::Vector3d& p : corners) e.add(p.x(), p.y(), p.z());
  return decidedByExtent(buffer, pass, e, role);
}

// The same for a chunk of screen triangles: the extent of their vertices. Worth it for tests (on
// env2's dragons at 500 px, 23% of the chunks of a triangle-level test were decided) but not for
// writes (55 of 292,709 chunks: a write mostly reaches pixels nothing has been written to).
bool decidedChunk(CpuDepthBuffer& buffer, const RasterPass& pass,
                  std::span<const ScreenTriangle> triangles, CpuCommand::Role role) {
  ScreenExtent e;
  for (const ScreenTriangle& t : triangles)
    for (int v = 0; v < 3; ++v) e.add(t.x[v], t.y[v], t.k[v]);
  return decidedByExtent(buffer, pass, e, role);
}

ScreenMatrix cubeToScreen(const ScreenMatrix& objectToScreen, const OrientedBox& box) {
  ScreenMatrix m;
  m.leftCols<3>() = objectToScreen.leftCols<3>() * box.axes * box.halfExtents.asDiagonal();
  m.col(3) = objectToScreen.leftCols<3>() * box.center + objectToScreen.col(3);
  return m;
}

// A box's deciding faces: as quads in conservative passes, as triangles in raw ones (whose
// pixel-centre rule is a triangle's). True when a test finds an occluded sample.
bool testBox(CpuDepthBuffer& buffer, const RasterPass& raster, const ScreenMatrix& cube,
             const BoxCorners& corners, CpuCommand::Role role,
             std::array<ScreenTriangle, kChunk>& chunk, RasterWork& work) {
  if (raster.conservative) {
    std::array<ScreenQuad, 6> quads;
    const std::size_t n = boxQuads(cube, corners, role, quads.data());
    return testQuadsUntilOccluded(buffer, raster, std::span<const ScreenQuad>(quads.data(), n),
                                  work) < n;
  }
  const std::size_t n = boxTriangles(cube, corners, role, chunk.data());
  return testTrianglesUntilOccluded(buffer, raster,
                                    std::span<const ScreenTriangle>(chunk.data(), n), work) < n;
}
void writeBox(CpuDepthBuffer& buffer, const RasterPass& raster, const ScreenMatrix& cube,
              const BoxCorners& corners, CpuCommand::Role role,
              std::array<ScreenTriangle, kChunk>& chunk, RasterWork& work) {
  if (raster.conservative) {
    std::array<ScreenQuad, 6> quads;
    const std::size_t n = boxQuads(cube, corners, role, quads.data());
    writeQuads(buffer, raster, std::span<const ScreenQuad>(quads.data(), n), work);
    return;
  }
  const std::size_t n = boxTriangles(cube, corners, role, chunk.data());
  writeTriangles(buffer, raster, std::span<const ScreenTriangle>(chunk.data(), n), work);
}

void runTest(CpuDepthBuffer& buffer, const RasterPass& raster, const CpuCommandList& list,
             const CpuCommand& c, std::uint8_t* answers, RasterWork& work) {
  std::array<ScreenTriangle, kChunk> chunk;
  if (c.source == CpuCommand::Source::Boxes) {
    for (std::uint32_t b = 0; b < c.count; ++b) {
      const ScreenMatrix cube = cubeToScreen(c.toScreen, list.boxes[c.first + b]);
      const BoxCorners corners = cubeCorners(cube);
      if (list.decideByBounds && decidedByCorners(buffer, raster, corners, c.role)) continue;
      if (testBox(buffer, raster, cube, corners, c.role, chunk, work)) {
        answers[c.query + (c.answerEach ? b : 0)] = 0;
        if (!c.answerEach) return;
      }
    }
    return;
  }
  if (list.decideByBounds && decidedByBounds(buffer, raster, c.toScreen, c.meshBox, c.role))
    return;
  for (std::uint32_t done = 0; done < c.count;) {
    const std::uint32_t at = done;
    const std::size_t n = fillChunk(list, c, done, chunk);
    const std::span<const ScreenTriangle> tris(chunk.data(), n);
    if (list.decideByBounds && decidedChunk(buffer, raster, tris, c.role)) continue;
    if (c.answerEach) {
      // Every triangle is kept (winding is 0 for batches): entry i answers triangle at + i.
      testEachTriangle(buffer, raster, tris, answers + c.query + at, work);
    } else if (testTrianglesUntilOccluded(buffer, raster, tris, work) < n) {
      answers[c.query] = 0;
      return;  // one occluded sample decides the piece
    }
  }
}

}  // namespace

void runWrite(CpuDepthBuffer& buffer, const RasterPass& raster, const CpuCommandList& list,
              const CpuCommand& c, RasterWork& work) {
  std::array<ScreenTriangle, kChunk> chunk;
  if (c.source == CpuCommand::Source::Boxes) {
    for (std::uint32_t b = 0; b < c.count; ++b) {
      const ScreenMatrix cube = cubeToScreen(c.toScreen, list.boxes[c.first + b]);
      const BoxCorners corners = cubeCorners(cube);
      if (list.decideByBounds && decidedByCorners(buffer, raster, corners, c.role)) continue;
      writeBox(buffer, raster, cube, corners, c.role, chunk, work);
    }
    return;
  }
  if (list.decideByBounds && decidedByBounds(buffer, raster, c.toScreen, c.meshBox, c.role))
    return;
  for (std::uint32_t done = 0; done < c.count;) {
    const std::size_t n = fillChunk(list, c, done, chunk);
    writeTriangles(buffer, raster, std::span<const ScreenTriangle>(chunk.data(), n), work);
  }
}

void runPass(CpuDepthBuffer& buffer, const CpuPass& pass, const CpuCommandList& list,
             std::uint8_t* answers, RasterWork& work,
             std::span<const CpuFootprint* const> footprints) {
  if (pass.clears) buffer.clear(pass.clearValue);
  for (std::uint32_t i = pass.firstCommand; i < pass.endCommand; ++i) {
    const CpuCommand& c = list.commands[i];
    if (c.role == CpuCommand::Role::Test)
      runTest(buffer, pass.raster, list, c, answers, work);
    else if (i < footprints.size() && footprints[i] != nullptr)
      mergeFootprint(buffer, pass.raster, *footprints[i], work);
    else
      runWrite(buffer, pass.raster, list, c, work);
  }
}

}  // namespace cdb
