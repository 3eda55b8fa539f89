#include "culling/visibility/cpu/CpuMeshBounds.h"

#include <unordered_map>

#include "scenes/MeshMeasures.h"

namespace cdb {

std::vector<CpuMeshBounds> meshBoundsOf(const SceneGeometry& scene) {
  std::vector<CpuMeshBounds> all;
  all.reserve(scene.meshes.size());
  for (const Mesh& m : scene.meshes) {
    CpuMeshBounds& b = all.emplace_back();
    const double volume = isClosedMesh(m) ? signedVolume(m) : 0.0;
    b.winding = volume > 0 ? 1 : volume < 0 ? -1 : 0;
    b.triangles.reserve(m.triangles.size());
    for (const Triangle& t : m.triangles) {
      Eigen::AlignedBox3f box(m.vertices[t[0]]);
      box.extend(m.vertices[t[1]]).extend(m.vertices[t[2]]);
      b.triangles.push_back(box);
    }
    b.cornersInChunk.resize(m.triangles.size());
    std::unordered_map<std::uint32_t, std::uint8_t> local;
    for (std::size_t first = 0; first < b.triangles.size(); first += kChunkTriangles) {
      Eigen::AlignedBox3f chunk;
      const std::size_t end = std::min<std::size_t>(first + kChunkTriangles, b.triangles.size());
      b.chunkVertexStart.push_back(static_cast<std::uint32_t>(b.chunkVertices.size()));
      local.clear();
      for (std::size_t t = first; t < end; ++t) {
        chunk.extend(b.triangles[t]);
        for (int v = 0; v < 3; ++v) {
          const std::uint32_t vertex = m.triangles[t][v];
          const auto [at, added] =
              local.try_emplace(vertex, static_cast<std::uint8_t>(local.size()));
          if (added) b.chunkVertices.push_back(vertex);
          b.cornersInChunk[t][v] = at->second;
        }
      }
      b.chunks.push_back(chunk);
    }
    b.chunkVertexStart.push_back(static_cast<std::uint32_t>(b.chunkVertices.size()));
    for (std::size_t first = 0; first < b.triangles.size(); first += kPartTriangles) {
      Eigen::AlignedBox3f part;
      const std::size_t end = std::min<std::size_t>(first + kPartTriangles, b.triangles.size());
      for (std::size_t t = first; t < end; ++t) part.extend(b.triangles[t]);
      b.parts.push_back(part);
    }
  }
  return all;
}

}  // namespace cdb
