#include "scenes/MeshMeasures.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>
#include <utility>
#include <vector>

namespace cdb {

std::vector<std::uint32_t> weldedVertexIds(const Mesh& mesh) {
  const auto key = [&](std::uint32_t i) {
    const auto& v = mesh.vertices[i];
    return std::make_tuple(v.x(), v.y(), v.z());
  };
  std::vector<std::uint32_t> order(mesh.vertices.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); });
  std::vector<std::uint32_t> id(mesh.vertices.size());
  std::uint32_t next = 0;
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k > 0 && key(order[k]) != key(order[k - 1])) ++next;
    id[order[k]] = next;
  }
  return id;
}

bool isClosedMesh(const Mesh& mesh) {
  const std::size_t vertexCount = mesh.vertices.size();
  for (const auto& t : mesh.triangles) {
    if (t[0] >= vertexCount || t[1] >= vertexCount || t[2] >= vertexCount) return false;
  }
  const std::vector<std::uint32_t> id = weldedVertexIds(mesh);
  using Edge = std::pair<std::uint32_t, std::uint32_t>;
  std::vector<Edge> edges;  // directed, as the triangles run along them
  edges.reserve(mesh.triangles.size() * 3);
  for (const auto& t : mesh.triangles) {
    const std::uint32_t a = id[t[0]], b = id[t[1]], c = id[t[2]];
    if (a == b || b == c || c == a) continue;
    edges.emplace_back(a, b);
    edges.emplace_back(b, c);
    edges.emplace_back(c, a);
  }
  if (edges.empty()) return false;
  std::sort(edges.begin(), edges.end());
  // A directed edge used twice means a third triangle or a flipped one: not a closed 2-manifold.
  if (std::adjacent_find(edges.begin(), edges.end()) != edges.end()) return false;
  return std::all_of(edges.begin(), edges.end(), [&](const Edge& e) {
    return std::binary_search(edges.begin(), edges.end(), Edge{e.second, e.first});
  });
}

double signedVolume(const Mesh& mesh) {
  double sixTimesVolume = 0.0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>();
    const Eigen::Vector3d b = mesh.vertices[t[1]].cast<double>();
    const Eigen::Vector3d c = mesh.vertices[t[2]].cast<double>();
    sixTimesVolume += a.dot(b.cross(c));
  }
  return sixTimesVolume / 6.0;
}

BoundingSphere boundingSphere(const Mesh& mesh) {
  BoundingSphere sphere;
  if (mesh.vertices.empty()) return sphere;
  sphere.centre = mesh.bounds().center();
  double radiusSquared = 0.0;
  for (const auto& v : mesh.vertices) {
    radiusSquared = std::max(radiusSquared, (v.cast<double>() - sphere.centre).squaredNorm());
  }
  sphere.radius = std::sqrt(radiusSquared);
  return sphere;
}

}  // namespace cdb
