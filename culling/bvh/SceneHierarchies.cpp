#include "culling/bvh/SceneHierarchies.h"

#include <map>
#include <mutex>
#include <tuple>

#include "core/Fnv1a.h"
#include "culling/bvh/ObbFitting.h"

namespace cdb {

namespace {

// The counts ride along with the hash so that a hash collision would also need equal sizes.
struct TreeKey {
  std::uint64_t contentHash = 0;
  std::size_t vertices = 0;
  std::size_t triangles = 0;
  int branching = 0;
  int leafTriangles = 0;
  double offset = 0;
  bool optimized = false;

  auto tie() const {
    return std::tie(contentHash, vertices, triangles, branching, leafTriangles, offset, optimized);
  }
  bool operator<(const TreeKey& o) const { return tie() < o.tie(); }
};

TreeKey keyOf(const Mesh& mesh, const ObbTreeOptions& options) {
  // FNV-1a over the raw bytes: a content fingerprint, not a security hash.
  Fnv1a h;
  h.bytes(mesh.vertices.data(), mesh.vertices.size() * sizeof(mesh.vertices[0]));
  h.bytes(mesh.triangles.data(), mesh.triangles.size() * sizeof(mesh.triangles[0]));
  return {h.value(),
          mesh.vertices.size(),
          mesh.triangles.size(),
          options.branching,
          options.leafTriangles,
          options.offset,
          options.optimized};
}

struct TreeCache {
  std::mutex mutex;
  std::map<TreeKey, std::shared_ptr<const MeshHierarchy>> trees;
  std::uint64_t builds = 0;
};

TreeCache& cache() {
  static TreeCache c;
  return c;
}

}  // namespace

ObbTreeOptions hierarchyOptions(const Mesh& mesh, const HierarchySpec& spec) {
  ObbTreeOptions options;
  options.branching = spec.branching;
  options.leafTriangles = spec.leafTriangles;
  options.offset = spec.offset * mesh.bounds().diagonal().norm();
  return options;
}

std::shared_ptr<const MeshHierarchy> cachedHierarchy(const Mesh& mesh,
                                                     const ObbTreeOptions& options) {
  const TreeKey key = keyOf(mesh, options);
  TreeCache& c = cache();
  // Held during the build: a second caller for the same mesh waits instead of building it again.
  std::lock_guard lock(c.mutex);
  auto& slot = c.trees[key];
  if (!slot) {
    auto h = std::make_shared<MeshHierarchy>(MeshHierarchy{ObbTree::build(mesh, options), {}});
    h->ownBoxes.reserve(h->tree.nodes().size());
    for (const ObbTreeNode& node : h->tree.nodes()) {
      const auto tris = h->tree.triangles(node);
      const OrientedBox own =
          options.optimized ? fitOptimizedObb(mesh, tris) : fitCovarianceObb(mesh, tris);
      h->ownBoxes.push_back(grown(own, options.offset));
    }
    slot = std::move(h);
    ++c.builds;
  }
  return slot;
}

std::shared_ptr<const ObbTree> cachedObbTree(const Mesh& mesh, const ObbTreeOptions& options) {
  auto h = cachedHierarchy(mesh, options);
  return {h, &h->tree};
}

std::uint64_t obbTreeBuilds() {
  TreeCache& c = cache();
  std::lock_guard lock(c.mutex);
  return c.builds;
}

void SceneHierarchies::build(const SceneGeometry& scene, const HierarchySpec& spec) {
  trees_.clear();
  for (const Mesh& mesh : scene.meshes)
    trees_.push_back(cachedHierarchy(mesh, hierarchyOptions(mesh, spec)));
  objectMesh_.clear();
  for (const SceneObject& object : scene.objects) objectMesh_.push_back(object.mesh);
}

}  // namespace cdb
