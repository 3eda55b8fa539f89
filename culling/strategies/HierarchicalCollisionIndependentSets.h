#pragma once
// The thesis' full approach (3.4.2): collision-independent sets (Algorithm 3.2) over each
// object's 8-ary OBB tree, coarse to fine, a different view axis per level.
//
// Level 0 runs the construction over every object, each object's geometry being its root box.
// Each further level looks along the next axis (x -> y -> z -> x ...) and runs the construction
// again on every set separately, with the set's own sorted endpoint list, each object's geometry
// being its active nodes there and its interval that of their union; a set splits into subsets,
// and nodes and objects are pruned on the way. A set whose active nodes are all leaves is done.
// The sets come out with their members restricted to the surviving leaves' triangles.
//
// Per set and pass, the first object drawn is not queried (nothing is drawn before it) and the
// last is not written (nothing is tested after it), and more generally a node apart along the
// view from everything drawn before (after) it is not queried (written); one depth clear per set
// per level (SharedFirst, then SharedSecond). See the .cpp for where this departs from
// Algorithm 3.2.
#include <array>
#include <cstdint>
#include <map>
#include <vector>

#include "culling/CisConstruction.h"
#include "culling/CullingStrategy.h"
#include "culling/SortedIntervals.h"
#include "culling/DetectorRegistry.h"
#include "culling/WorldBounds.h"
#include "culling/bvh/NodeFrontier.h"
#include "culling/bvh/SceneHierarchies.h"
#include "scenes/CullingSpec.h"

namespace cdb {

class HierarchicalCollisionIndependentSets final : public CullingStrategy {
 public:
  explicit HierarchicalCollisionIndependentSets(const DetectorOptions& options,
                                                HierarchicalCisOptions config = {});

  [[nodiscard]] std::string_view name() const override { return "ours"; }
  void attach(const SceneGeometry& scene, VisibilityBackend& backend) override;
  [[nodiscard]] CullingResult cull(const FrameInput& frame) override;

  // What the last frame did, beyond CullingCounters.
  struct FrameStats {
    std::vector<int> axes;            // view axis of each level
    std::uint64_t sortExchanges = 0;  // insertion-sort exchanges over every list
    std::uint64_t listsKept = 0;      // sorted lists carried over from the previous frame
    std::uint64_t listsBuilt = 0;     // sorted lists built from scratch
    // Node draws left out because the node is apart, along the view, from every object drawn
    // before it (queries) or after it (writes) in its pass.
    std::uint64_t queriesSkipped = 0;
    std::uint64_t writesSkipped = 0;
  };
  [[nodiscard]] const FrameStats& lastFrame() const { return stats_; }

 private:
  // A set under test at one level.
  struct SetRun {
    std::vector<ObjectId> objects;  // ascending ids; the slots of its sorted list
    CisConstruction cis;
    // The active nodes of all its objects, slot after slot: slot s owns the range
    // [firstNode[s], firstNode[s + 1]).
    std::vector<std::uint32_t> firstNode;
    std::vector<std::pair<double, double>> nodeIntervals;  // along the level's axis
    std::array<std::vector<QueryIndex>, 2> query;          // per pass (kNotQueried: none)
  };
  // A sorted list is kept across frames for every (level, axis, set of objects) that recurs.
  struct ListKey {
    std::uint32_t level = 0;
    int axis = 0;
    std::vector<ObjectId> objects;
    bool operator<(const ListKey& o) const;
  };
  struct KeptList {
    SortedIntervals sorted;
    std::uint64_t lastFrame = 0;
  };

  SortedIntervals& listFor(std::uint32_t level, int axis, const std::vector<ObjectId>& objects);
  void drawSet(SetRun& run, std::uint32_t level, int axis, std::span<const Pose> poses);
  // Splits the set from the fetched answers; appends the subsets (two members or more) to `out`.
  void splitSet(SetRun& run, std::vector<std::vector<ObjectId>>& out);
  // Whether the k-th active node of the object at `slot` was fully visible in `pass` (0 or 1).
  [[nodiscard]] bool nodeVisible(const SetRun& run, int pass, std::uint32_t slot,
                                 std::size_t k) const;

  DetectorOptions options_;
  HierarchicalCisOptions config_;
  const SceneGeometry* scene_ = nullptr;
  VisibilityBackend* backend_ = nullptr;
  SceneHierarchies hierarchies_;
  NodeFrontier frontier_;
  WorldBounds bounds_;  // the objects' world boxes, which clip the nodes' intervals
  std::map<ListKey, KeptList> lists_;
  std::uint64_t frameCount_ = 0;
  FrameStats stats_;
  // The sets under test at a level, kept from level to level and frame to frame (drawSet makes a
  // run afresh): their tables, sized for thousands of nodes, keep their memory, where made anew
  // they came from fresh pages (page faults) at every level of every frame.
  std::vector<SetRun> runs_;
  std::vector<std::uint8_t> visible_;                 // the level's query answers
  std::vector<std::uint8_t> bySlot_;                  // one answer per slot
  std::vector<std::uint8_t> keep_;                    // per active node of one object
  std::vector<std::pair<double, double>> intervals_;  // per slot of the set being drawn
  std::vector<double> laterNear_;                     // per position in a pass
  std::vector<double> laterFar_;
  std::vector<OrientedBox> batchBoxes_;  // one object's boxes queried (or written) at once
  std::vector<std::size_t> batchNodes_;  // where each queried box's answer goes
  // Per node of a set (SetRun::nodeIntervals): whether pass 1 and pass 2 query it.
  std::array<std::vector<std::uint8_t>, 2> queriedIn_;
  // Per slot: pass 1's answer of the first of its nodes both passes query (their batch).
  std::vector<QueryIndex> bothFirst_;
};

}  // namespace cdb
