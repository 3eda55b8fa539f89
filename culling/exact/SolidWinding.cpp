#include "culling/exact/SolidWinding.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <deque>
#include <limits>
#include <mutex>
#include <numeric>
#include <span>
#include <tuple>
#include <vector>

#include "core/Aabb.h"
#include "culling/exact/OrientationPredicates.h"
#include "culling/exact/SweepAndPrune.h"
#include "culling/exact/TriangleTriangle.h"
#include "scenes/MeshMeasures.h"

namespace cdb {

namespace {

using Corners = std::array<std::uint32_t, 3>;  // welded vertex ids

// Parts of the mesh: triangles joined across each edge (union-find with path halving).
class Parts {
 public:
  explicit Parts(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0u); }
  std::uint32_t root(std::uint32_t i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void join(std::uint32_t a, std::uint32_t b) { parent_[root(a)] = root(b); }

 private:
  std::vector<std::uint32_t> parent_;
};

// Points of one plane (that of triangle t, not collapsed) seen along the coordinate axis its
// normal is closest to: orientations taken in that view are those in the plane up to one sign, the
// same for all, exactly.
struct PlaneView {
  int drop = 0;
  PlaneView(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    (b - a).cross(c - a).cwiseAbs().maxCoeff(&drop);
  }
  [[nodiscard]] Eigen::Vector2d operator()(const Eigen::Vector3d& q) const {
    return {q[(drop + 1) % 3], q[(drop + 2) % 3]};
  }
};

}  // namespace

bool meetOnlyWhereShared(const std::array<std::uint32_t, 3>& ti,
                         const std::array<std::uint32_t, 3>& tj,
                         std::span<const Eigen::Vector3d> at) {
  int shared = 0;
  for (std::uint32_t v : ti) shared += static_cast<int>(std::count(tj.begin(), tj.end(), v));
  const auto p = [&](std::uint32_t v) -> const Eigen::Vector3d& { return at[v]; };
  if (shared == 0)
    return !trianglesIntersect(p(ti[0]), p(ti[1]), p(ti[2]), p(tj[0]), p(tj[1]), p(tj[2]));
  if (shared == 3) return false;  // the same corners twice
  // Rotate each so that its shared corners come first: (a, b, c) and (a, d, e), or (a, b, c) and
  // (a, b, d) for a shared edge.
  Corners a = ti, b = tj;
  const auto isShared = [](std::uint32_t v, const Corners& other) {
    return std::find(other.begin(), other.end(), v) != other.end();
  };
  if (shared == 1) {
    while (!isShared(a[0], tj)) std::rotate(a.begin(), a.begin() + 1, a.end());
    while (b[0] != a[0]) std::rotate(b.begin(), b.begin() + 1, b.end());
    using predicates::orient3d;
    if (orient3d(p(a[0]), p(a[1]), p(a[2]), p(b[1])) == 0 &&
        orient3d(p(a[0]), p(a[1]), p(a[2]), p(b[2])) == 0) {
      // Coplanar: near the corner each triangle is its wedge (the angle its two edges from the
      // corner span), and they meet beyond the corner exactly when the wedges do, that is when
      // an edge from the corner of one lies in the other's closed wedge.
      const PlaneView flat(p(a[0]), p(a[1]), p(a[2]));
      const Eigen::Vector2d o = flat(p(a[0]));
      const auto inWedge = [&](std::uint32_t v, const Corners& t) {
        const int turn = predicates::orient2d(o, flat(p(t[1])), flat(p(t[2])));
        return turn * predicates::orient2d(o, flat(p(t[1])), flat(p(v))) >= 0 &&
               turn * predicates::orient2d(o, flat(p(v)), flat(p(t[2]))) >= 0;
      };
      if (predicates::orient2d(o, flat(p(a[1])), flat(p(a[2]))) == 0 ||
          predicates::orient2d(o, flat(p(b[1])), flat(p(b[2]))) == 0)
        return false;  // a collapsed triangle: not decided
      return !inWedge(b[1], a) && !inWedge(b[2], a) && !inWedge(a[1], b) && !inWedge(a[2], b);
    }
    // Not coplanar: the two planes meet in a line through the shared corner, which each triangle
    // meets in a segment from that corner. If the segments overlap beyond it, the shorter one ends
    // on the edge opposite the corner of its triangle, which then meets the other triangle.
    // Edge (1, 2) of `edge` against `triangle`. Ends strictly on one side of its plane: apart.
    // Strictly on both sides: the edge's line crosses the plane once, inside the closed triangle
    // exactly when it passes no two of the triangle's edges in opposite senses (Pluecker signs).
    // An end in the plane: the general test (whose segment, a triangle with a repeated corner,
    // takes the exact arithmetic).
    const auto edgeMisses = [&](const Corners& edge, const Corners& triangle) {
      const Eigen::Vector3d &p0 = p(edge[1]), &p1 = p(edge[2]);
      const Eigen::Vector3d &u = p(triangle[0]), &v = p(triangle[1]), &w = p(triangle[2]);
      const int s1 = orient3d(u, v, w, p0), s2 = orient3d(u, v, w, p1);
      if (s1 == s2 && s1 != 0) return true;
      if (s1 == -s2 && s1 != 0) {
        const int uv = orient3d(p0, p1, u, v), vw = orient3d(p0, p1, v, w);
        const int wu = orient3d(p0, p1, w, u);
        const bool positive = uv > 0 || vw > 0 || wu > 0, negative = uv < 0 || vw < 0 || wu < 0;
        return positive && negative;
      }
      return !trianglesIntersect(p0, p1, p1, u, v, w);
    };
    return edgeMisses(a, b) && edgeMisses(b, a);
  }
  // A shared edge: not coplanar, the triangles meet on the line of the edge only, so in the edge;
  // coplanar, there only if their third corners lie on opposite sides of it.
  while (isShared(a[2], tj)) std::rotate(a.begin(), a.begin() + 1, a.end());
  const std::uint32_t d =
      *std::find_if(tj.begin(), tj.end(), [&](std::uint32_t v) { return v != a[0] && v != a[1]; });
  if (predicates::orient3d(p(a[0]), p(a[1]), p(a[2]), p(d)) != 0) return true;
  const PlaneView flat(p(a[0]), p(a[1]), p(a[2]));
  const int third = predicates::orient2d(flat(p(a[0])), flat(p(a[1])), flat(p(a[2])));
  const int other = predicates::orient2d(flat(p(a[0])), flat(p(a[1])), flat(p(d)));
  return third != 0 && other == -third;
}

int solidWinding(const Mesh& mesh) {
  if (!isClosedMesh(mesh)) return 0;
  const std::vector<std::uint32_t> id = weldedVertexIds(mesh);
  std::vector<Eigen::Vector3d> at(
      mesh.vertices.empty() ? 0 : 1 + *std::max_element(id.begin(), id.end()));
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    at[id[v]] = mesh.vertices[v].cast<double>();
  const std::size_t n = mesh.triangles.size();
  std::vector<Corners> corners(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& t = mesh.triangles[i];
    corners[i] = {id[t[0]], id[t[1]], id[t[2]]};
    if (corners[i][0] == corners[i][1] || corners[i][1] == corners[i][2] ||
        corners[i][2] == corners[i][0])
      return 0;  // collapsed
  }

  // Parts: each directed edge joins its triangle to the one running along it the other way (a
  // closed mesh has exactly one).
  std::vector<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>> edges;
  edges.reserve(3 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int e = 0; e < 3; ++e)
      edges.emplace_back(corners[i][e], corners[i][(e + 1) % 3], static_cast<std::uint32_t>(i));
  std::sort(edges.begin(), edges.end());
  Parts parts(n);
  for (const auto& [a, b, t] : edges) {
    const auto reverse = std::lower_bound(edges.begin(), edges.end(), std::make_tuple(b, a, 0u));
    parts.join(t, std::get<2>(*reverse));
  }

  // Each part's signed volume (six times it, about the mesh's centre), with a bound on its
  // rounding: every part's sign must be decided and the same.
  const Eigen::Vector3d centre = mesh.bounds().center();
  std::vector<double> volume(n, 0.0), magnitude(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d a = at[corners[i][0]] - centre, b = at[corners[i][1]] - centre,
                          c = at[corners[i][2]] - centre;
    const std::uint32_t r = parts.root(static_cast<std::uint32_t>(i));
    volume[r] += a.dot(b.cross(c));
    magnitude[r] += a.norm() * b.norm() * c.norm();
  }
  const double relativeError =
      (static_cast<double>(n) + 16.0) * std::numeric_limits<double>::epsilon();
  int sign = 0;
  for (std::size_t r = 0; r < n; ++r) {
    if (parts.root(static_cast<std::uint32_t>(r)) != r) continue;
    if (!(std::abs(volume[r]) > relativeError * magnitude[r])) return 0;
    const int s = volume[r] > 0 ? 1 : -1;
    if (sign != 0 && s != sign) return 0;
    sign = s;
  }

  // No two triangles meet other than where they share corners.
  std::vector<Aabb> boxes(n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t v : corners[i]) boxes[i].extend(at[v]);
  const std::vector<IndexPair> pairs = sweepAndPrune(boxes);
  std::atomic<bool> apart = true;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pairs.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k != range.end(); ++k) {
                        if (!apart.load(std::memory_order_relaxed)) return;
                        const IndexPair& pair = pairs[k];
                        if (!meetOnlyWhereShared(corners[pair.i], corners[pair.j], at))
                          apart.store(false, std::memory_order_relaxed);
                      }
                    });
  return apart.load() ? sign : 0;
}

namespace {

template <class T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

}  // namespace

int rememberedSolidWinding(const Mesh& mesh) {
  struct Remembered {
    std::vector<Eigen::Vector3f> vertices;
    std::vector<Triangle> triangles;
    int winding = 0;
    [[nodiscard]] std::size_t bytes() const {
      return vertices.size() * sizeof(Eigen::Vector3f) + triangles.size() * sizeof(Triangle);
    }
  };
  static std::mutex mutex;
  static std::deque<Remembered> recent;  // newest first
  static std::size_t recentBytes = 0;
  // At most 1,024 meshes and 64 MiB of copies (a mesh larger than that is checked at every
  // attach). A scene of many small meshes attached again and again (a test's 40 spheres) needs
  // them all; a lookup compares sizes first.
  constexpr std::size_t kMostMeshes = 1024, kMostBytes = std::size_t{64} << 20;
  {
    const std::lock_guard lock(mutex);
    for (const Remembered& r : recent)
      if (sameBits(r.vertices, mesh.vertices) && sameBits(r.triangles, mesh.triangles))
        return r.winding;
  }
  const int winding = solidWinding(mesh);
  if (mesh.vertices.size() * sizeof(Eigen::Vector3f) + mesh.triangles.size() * sizeof(Triangle) >
      kMostBytes)
    return winding;
  Remembered kept{mesh.vertices, mesh.triangles, winding};
  const std::lock_guard lock(mutex);
  recentBytes += kept.bytes();
  recent.push_front(std::move(kept));
  while (recent.size() > kMostMeshes || recentBytes > kMostBytes) {
    recentBytes -= recent.back().bytes();
    recent.pop_back();
  }
  return winding;
}

}  // namespace cdb
