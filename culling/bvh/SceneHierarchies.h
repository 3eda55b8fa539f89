#pragma once
// The OBB tree (thesis 3.4.1) of every mesh of a scene. Trees are built once per mesh content and
// options and shared process-wide, because a sweep creates a strategy per cell (resolution,
// repeat) on the same meshes, and the dragon's tree takes far longer to build than a frame.
#include <cstdint>
#include <memory>
#include <vector>

#include "culling/bvh/ObbTree.h"
#include "scenes/CullingSpec.h"
#include "scenes/SceneGeometry.h"

namespace cdb {

// The tree options of a mesh under a config: branching and leaf size as given, and the offset (a
// fraction of the mesh's bounding-box diagonal in the config) as an absolute distance in mesh
// units.
[[nodiscard]] ObbTreeOptions hierarchyOptions(const Mesh& mesh, const HierarchySpec& spec);

// A mesh's tree and, per node, the box fitted to the node's own triangles (with the offset).
// The tree grows each parent's box to contain its children's, which nesting needs but a
// coarse-to-fine visibility traversal does not: it only needs each node's box to hold the node's
// triangles, since pruning a node says its triangles touch nothing, and its children's boxes
// hold theirs. The own boxes are tighter, most of all near the root (a torus' root box grows
// ~1.4 times per axis), and a tighter box is fully visible more often.
struct MeshHierarchy {
  ObbTree tree;
  std::vector<OrientedBox> ownBoxes;  // per node of tree
};

// The hierarchy of `mesh` under `options`, built on the first request for that content (vertex
// and triangle bytes) and options and returned from the cache afterwards. Thread-safe.
[[nodiscard]] std::shared_ptr<const MeshHierarchy> cachedHierarchy(const Mesh& mesh,
                                                                   const ObbTreeOptions& options);
// Its tree alone.
[[nodiscard]] std::shared_ptr<const ObbTree> cachedObbTree(const Mesh& mesh,
                                                           const ObbTreeOptions& options);

// Trees built by cachedObbTree since the process started (cache misses), for tests.
[[nodiscard]] std::uint64_t obbTreeBuilds();

class SceneHierarchies {
 public:
  void build(const SceneGeometry& scene, const HierarchySpec& spec);

  [[nodiscard]] const ObbTree& ofMesh(std::uint32_t mesh) const { return trees_[mesh]->tree; }
  [[nodiscard]] const ObbTree& ofObject(ObjectId object) const {
    return trees_[objectMesh_[object]]->tree;
  }
  // The box fitted to the node's own triangles (MeshHierarchy::ownBoxes).
  [[nodiscard]] const OrientedBox& ownBox(ObjectId object, std::uint32_t node) const {
    return trees_[objectMesh_[object]]->ownBoxes[node];
  }

 private:
  std::vector<std::shared_ptr<const MeshHierarchy>> trees_;  // per mesh
  std::vector<std::uint32_t> objectMesh_;                    // per object
};

}  // namespace cdb
