#include "culling/visibility/cpu/CpuMeshBounds.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <span>

#include "culling/visibility/cpu/CpuPassSpace.h"

namespace cdb {

namespace {

// The low 10 bits of v spread to every third bit.
std::uint32_t spreadBits(std::uint32_t v) {
  v &= 0x3ffu;
  v = (v | (v << 16)) & 0x030000ffu;
  v = (v | (v << 8)) & 0x0300f00fu;
  v = (v | (v << 4)) & 0x030c30c3u;
  v = (v | (v << 2)) & 0x09249249u;
  return v;
}

}  // namespace

std::vector<std::uint32_t> drawOrderOf(const Mesh& mesh) {
  const std::size_t n = mesh.triangles.size();
  Eigen::AlignedBox3f box;
  for (const Eigen::Vector3f& v : mesh.vertices)
    if (v.allFinite()) box.extend(v);
  const float extent = box.isEmpty() ? 0.f : box.sizes().maxCoeff();
  const float scale = extent > 0.f ? 1023.f / extent : 0.f;
  std::vector<std::uint32_t> code(n, 0);
  for (std::size_t t = 0; t < n; ++t) {
    const Triangle& tri = mesh.triangles[t];
    const Eigen::Vector3f centroid =
        (mesh.vertices[tri[0]] + mesh.vertices[tri[1]] + mesh.vertices[tri[2]]) / 3.f;
    if (!centroid.allFinite()) continue;
    std::uint32_t cell[3];
    for (int a = 0; a < 3; ++a)
      cell[a] =
          static_cast<std::uint32_t>(std::clamp((centroid[a] - box.min()[a]) * scale, 0.f, 1023.f));
    code[t] = spreadBits(cell[0]) | spreadBits(cell[1]) << 1 | spreadBits(cell[2]) << 2;
  }
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return code[a] < code[b]; });
  return order;
}

namespace {

// How compact the chunks of `order` are: the summed extents of their boxes (a chunk much smaller
// than a tile touches more tiles as its rectangle's width plus height grows, from any direction).
double chunkExtents(const Mesh& mesh, std::span<const std::uint32_t> order) {
  double extents = 0.0;
  for (std::size_t first = 0; first < order.size(); first += kChunkTriangles) {
    Eigen::AlignedBox3f box;
    const std::size_t end = std::min<std::size_t>(first + kChunkTriangles, order.size());
    for (std::size_t p = first; p < end; ++p)
      for (const std::uint32_t v : mesh.triangles[order[p]])
        if (mesh.vertices[v].allFinite()) box.extend(mesh.vertices[v]);
    if (box.isEmpty()) continue;
    extents += box.sizes().cast<double>().sum();
  }
  return extents;
}

}  // namespace

std::vector<std::uint32_t> chosenDrawOrder(const Mesh& mesh) {
  std::vector<std::uint32_t> own(mesh.triangles.size());
  std::iota(own.begin(), own.end(), 0u);
  std::vector<std::uint32_t> morton = drawOrderOf(mesh);
  return chunkExtents(mesh, morton) < chunkExtents(mesh, own) ? morton : own;
}

std::vector<CpuMeshBounds> meshBoundsOf(const SceneGeometry& scene) {
  std::vector<CpuMeshBounds> all;
  all.reserve(scene.meshes.size());
  for (const Mesh& m : scene.meshes) {
    CpuMeshBounds& b = all.emplace_back();
    b.winding = meshWinding(m);
    const std::size_t n = m.triangles.size();
    b.order = chosenDrawOrder(m);
    b.position.resize(n);
    for (std::size_t p = 0; p < n; ++p) b.position[b.order[p]] = static_cast<std::uint32_t>(p);
    b.triangles.reserve(n);
    for (const std::uint32_t tri : b.order) {
      const Triangle& t = m.triangles[tri];
      Eigen::AlignedBox3f box(m.vertices[t[0]]);
      box.extend(m.vertices[t[1]]).extend(m.vertices[t[2]]);
      b.triangles.push_back(box);
    }
    const std::size_t chunks = (n + kChunkTriangles - 1) / kChunkTriangles;
    b.chunkCorners.resize(chunks * kChunkCornerRows * kChunkTriangles);
    for (std::size_t p = 0; p < chunks * kChunkTriangles; ++p) {
      const Triangle& t = m.triangles[b.order[std::min(p, n - 1)]];
      float* rows =
          b.chunkCorners.data() + p / kChunkTriangles * kChunkCornerRows * kChunkTriangles;
      for (int v = 0; v < 3; ++v)
        for (int a = 0; a < 3; ++a)
          rows[(3 * v + a) * kChunkTriangles + p % kChunkTriangles] = m.vertices[t[v]][a];
    }
    for (std::size_t first = 0; first < n; first += kPartTriangles) {
      Eigen::AlignedBox3f part;
      const std::size_t end = std::min<std::size_t>(first + kPartTriangles, n);
      for (std::size_t p = first; p < end; ++p) part.extend(b.triangles[p]);
      b.parts.push_back(part);
    }
  }
  return all;
}

}  // namespace cdb
