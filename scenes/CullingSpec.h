#pragma once
// The `culling` section of a scenario config (configs/README.md): how visibility is answered, the
// OBB trees, and each strategy's own options. Plain values with their defaults; the loader fills
// them, the registry hands each strategy its part. They live here, not beside the strategies, so
// that scenes/ can fill them without depending on culling/.
#include <optional>
#include <string>

namespace cdb {

// How the visibility tests are answered: one backend for every image-based strategy of a run.
struct VisibilitySpec {
  // Backend by registry name; empty = the harness' default (VisibilityBackendRegistry::kDefault).
  // Checked against the registry by the harness.
  std::string backend;
  bool conservative = true;      // widen by >= 1 pixel and offset depth (no contact lost)
  double rawDepthOffset = 1e-5;  // the raw mode's small depth offset, in NDC depth units
  int threads = 0;               // worker threads of CPU backends (0 = every core)
};

// A mesh's OBB tree (thesis 3.4.1), for the strategies with a hierarchy.
struct HierarchySpec {
  int branching = 8;      // children per split: 2, 4 or 8 (the thesis' tree is 8-ary)
  int leafTriangles = 8;  // a node with at most this many triangles is a leaf
  double offset = 1e-3;   // box enlargement against rounding, a fraction of the mesh's diagonal
};

// A view axis given in a config: 0 = x, 1 = y, 2 = z; unset ("auto") = chosen per frame.
using AxisChoice = std::optional<int>;

// cis (thesis 3.3).
struct CisOptions {
  // View axis. Unset: chosen per frame as the axis along which the object centres spread most
  // (largest variance), where intervals overlap least and sets separate best. Pass 1 looks along
  // +axis, so "far" is the larger coordinate.
  AxisChoice axis;
};

// ours (thesis 3.4).
struct HierarchicalCisOptions {
  // Level 0's view axis; level k looks along (axis + k) mod 3. Unset: chosen per frame as the
  // axis along which the root boxes' centres spread most, where the first sets separate best.
  AxisChoice firstAxis;
  HierarchySpec hierarchy;
};

// cullide_bvh.
struct CullideWithHierarchyOptions {
  HierarchySpec hierarchy;
};

// The options of the strategies that have any, by strategy.
struct StrategySpecs {
  CisOptions cis;
  HierarchicalCisOptions ours;
  CullideWithHierarchyOptions cullideBvh;
};

struct CullingSpec {
  VisibilitySpec visibility;
  StrategySpecs strategies;
};

}  // namespace cdb
