#include "culling/strategies/HierarchicalCollisionIndependentSets.h"

#include <algorithm>
#include <limits>
#include <span>
#include <tuple>

#include "culling/ViewAxis.h"

// Where this departs from Algorithm 3.2 run per set, and why:
//  - Pass 2 queries every object of the set (but the first drawn), not only those fully visible
//    in pass 1. Nodes are pruned when fully visible in both passes, and the members of pass-1
//    sets, the objects that may collide, are the ones whose nodes most need pruning; and since
//    pass 2 then no longer depends on pass 1's answers, every set of a level is drawn before one
//    fetch, instead of two synchronisations per set. The construction reads pass 2's answers
//    only where Algorithm 3.2 would have tested, and node pruning only where pass 1 found the
//    node visible: so a node's pass-2 answer is fetched ANDed with its pass-1 answer (gated,
//    VisibilityBackend::gateAnswers), and a backend need not test it where pass 1 found it
//    occluded, as Algorithm 3.2 does not.
//  - A node is pruned when fully visible in both passes: pass 1 tests it against every object of
//    farther Min in the set, pass 2 against every one of nearer Min, so its triangles touch no
//    other object's of the set; objects outside the set cannot touch them (earlier levels' sets).
//  - Intervals are those of the triangles a node may hold (its box's, clipped to the object's
//    world box), not of the box drawn. CisConstruction's argument holds with "collide" read as
//    "triangles touch": touching triangles lie in both objects' intervals, and a box containing
//    a triangle that touches a drawn triangle (inside a drawn box) is not fully visible.
// An object's nodes are all queried before any of them is written, so they never occlude each
// other; the object is fully visible when all of them are.

namespace cdb {

namespace {
constexpr QueryIndex kNotQueried = std::numeric_limits<QueryIndex>::max();
}  // namespace

bool HierarchicalCollisionIndependentSets::ListKey::operator<(const ListKey& o) const {
  return std::tie(level, axis, objects) < std::tie(o.level, o.axis, o.objects);
}

HierarchicalCollisionIndependentSets::HierarchicalCollisionIndependentSets(
    const DetectorOptions& options, HierarchicalCisOptions config)
    : options_(options), config_(config) {}

void HierarchicalCollisionIndependentSets::attach(const SceneGeometry& scene,
                                                  VisibilityBackend& backend) {
  scene_ = &scene;
  backend_ = &backend;
  hierarchies_.build(scene, config_.hierarchy);
  frontier_.attach(scene, hierarchies_);
  bounds_.attach(scene);
  lists_.clear();
}

SortedIntervals& HierarchicalCollisionIndependentSets::listFor(
    std::uint32_t level, int axis, const std::vector<ObjectId>& objects) {
  KeptList& kept = lists_[ListKey{level, axis, objects}];
  kept.lastFrame = frameCount_;
  return kept.sorted;
}

void HierarchicalCollisionIndependentSets::drawSet(SetRun& run, std::uint32_t level, int axis,
                                                   std::span<const Pose> poses) {
  const Eigen::Vector3d direction = Eigen::Vector3d::Unit(axis);
  const std::size_t n = run.objects.size();
  intervals_.clear();
  run.nodeIntervals.clear();
  run.firstNode.clear();
  Aabb bounds;
  for (ObjectId o : run.objects) {
    const auto first = static_cast<std::uint32_t>(run.nodeIntervals.size());
    run.firstNode.push_back(first);
    (void)frontier_.nodeIntervals(o, poses[o], direction, run.nodeIntervals);
    // Node boxes are loose (a parent grows to hold its children's boxes), the object's world box
    // is not: every triangle lies in both, so each node's interval is clipped to the object's.
    // The intervals then order, split and skip on the triangles' extent, which is all that the
    // safety argument needs (see the top of this file); the boxes drawn stay as they are.
    const auto [lo, hi] = projectAabb(bounds_[o], direction);
    std::pair<double, double> object{hi, lo};
    for (std::size_t j = first; j < run.nodeIntervals.size(); ++j) {
      auto& iv = run.nodeIntervals[j];
      iv = {std::max(iv.first, lo), std::min(iv.second, hi)};
      object = {std::min(object.first, iv.first), std::max(object.second, iv.second)};
    }
    intervals_.push_back(object);
    bounds.extend(frontier_.worldBounds(o, poses[o]));
  }
  run.firstNode.push_back(static_cast<std::uint32_t>(run.nodeIntervals.size()));
  SortedIntervals& sorted = listFor(level, axis, run.objects);
  stats_.sortExchanges += sorted.update(run.objects, intervals_);
  ++(sorted.lastUpdateRebuilt() ? stats_.listsBuilt : stats_.listsKept);
  run.cis.reset(sorted);

  // Pass 1 far to near along +axis, pass 2 the reverse looking along -axis. In a pass's depth
  // (the coordinate along its view), a node is queried only when its depth range overlaps that
  // of some object drawn before it, and written only when it overlaps some object drawn after
  // it: otherwise a plane across the view separates them (Lemma 1) and the answer is known. The
  // first object drawn is thus never queried and the last never written (3.4.2).
  const auto order = run.cis.passOneOrder();
  auto depthOf = [](int pass, std::pair<double, double> iv) {
    return pass == 0 ? iv : std::pair<double, double>{-iv.second, -iv.first};
  };
  // The slot drawn k-th in a pass.
  auto slotAt = [&](int pass, std::size_t k) { return order[pass == 0 ? k : n - 1 - k]; };
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // Which nodes each pass queries, known before either is drawn.
  for (int pass = 0; pass < 2; ++pass) {
    queriedIn_[pass].assign(run.nodeIntervals.size(), 0);
    double earlierNear = kInf;
    double earlierFar = -kInf;
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint32_t slot = slotAt(pass, k);
      for (std::uint32_t at = run.firstNode[slot]; at < run.firstNode[slot + 1]; ++at) {
        const auto d = depthOf(pass, run.nodeIntervals[at]);
        queriedIn_[pass][at] = d.second >= earlierNear && d.first <= earlierFar;
      }
      const auto d = depthOf(pass, intervals_[slot]);
      earlierNear = std::min(earlierNear, d.first);
      earlierFar = std::max(earlierFar, d.second);
    }
  }
  bothFirst_.assign(n, kNotQueried);
  ViewSpec view{direction, bounds, options_.resolution};
  for (int pass = 0; pass < 2; ++pass) {
    // Nearest near end and farthest far end of the objects drawn after position k.
    laterNear_.assign(n, kInf);
    laterFar_.assign(n, -kInf);
    for (std::size_t k = n - 1; k-- > 0;) {
      const auto d = depthOf(pass, intervals_[slotAt(pass, k + 1)]);
      laterNear_[k] = std::min(laterNear_[k + 1], d.first);
      laterFar_[k] = std::max(laterFar_[k + 1], d.second);
    }
    backend_->beginPass(view, pass == 0 ? DepthUse::SharedFirst : DepthUse::SharedSecond);
    run.query[pass].assign(run.nodeIntervals.size(), kNotQueried);
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint32_t slot = slotAt(pass, k);
      const ObjectId o = run.objects[slot];
      const auto nodes = frontier_.nodes(o);
      // Every node queried before any is written: an object does not occlude itself. The nodes
      // both passes query come first, as one batch of the same boxes in both: a node is kept
      // unless visible in both passes, and the sets read pass 2 only of objects fully visible in
      // pass 1, so pass 2's answers of them are gated by pass 1's (gateAnswers), and a backend
      // need not test in pass 2 what pass 1 found occluded. Then the nodes of this pass alone.
      for (const bool both : {true, false}) {
        batchBoxes_.clear();
        batchNodes_.clear();
        for (std::size_t j = 0; j < nodes.size(); ++j) {
          const std::size_t at = run.firstNode[slot] + j;
          if (queriedIn_[pass][at] && queriedIn_[1 - pass][at] == both) {
            batchBoxes_.push_back(frontier_.box(o, nodes[j]));
            batchNodes_.push_back(at);
          } else if (both && !queriedIn_[pass][at]) {
            ++stats_.queriesSkipped;
          }
        }
        const QueryIndex first = backend_->queryBoxes(o, batchBoxes_);
        for (std::size_t i = 0; i < batchNodes_.size(); ++i)
          run.query[pass][batchNodes_[i]] = first + static_cast<QueryIndex>(i);
        if (both && pass == 0) bothFirst_[slot] = first;
        if (both && pass == 1 && !batchNodes_.empty())
          backend_->gateAnswers(first, bothFirst_[slot],
                                static_cast<std::uint32_t>(batchNodes_.size()));
      }
      batchBoxes_.clear();
      for (std::size_t j = 0; j < nodes.size(); ++j) {
        const auto d = depthOf(pass, run.nodeIntervals[run.firstNode[slot] + j]);
        if (d.second >= laterNear_[k] && d.first <= laterFar_[k])
          batchBoxes_.push_back(frontier_.box(o, nodes[j]));
        else
          ++stats_.writesSkipped;
      }
      backend_->writeBoxes(o, batchBoxes_);
    }
    view.direction = -direction;
  }
}

bool HierarchicalCollisionIndependentSets::nodeVisible(const SetRun& run, int pass,
                                                       std::uint32_t slot, std::size_t k) const {
  const QueryIndex q = run.query[pass][run.firstNode[slot] + k];
  return q == kNotQueried || visible_[q];
}

void HierarchicalCollisionIndependentSets::splitSet(SetRun& run,
                                                    std::vector<std::vector<ObjectId>>& out) {
  const std::size_t n = run.objects.size();
  bySlot_.assign(n, 0);
  for (int pass = 0; pass < 2; ++pass) {
    for (std::uint32_t slot = 0; slot < n; ++slot) {
      const std::size_t count = frontier_.nodes(run.objects[slot]).size();
      bool all = true;
      for (std::size_t k = 0; k < count && all; ++k) all = nodeVisible(run, pass, slot, k);
      bySlot_[slot] = all;
    }
    if (pass == 0)
      run.cis.firstPass(bySlot_);
    else
      run.cis.secondPass(bySlot_);
  }

  for (const auto& members : run.cis.sets()) {
    if (members.size() < 2) continue;
    std::vector<ObjectId> subset;
    for (std::uint32_t slot : members) {
      const ObjectId o = run.objects[slot];
      const std::size_t count = frontier_.nodes(o).size();
      keep_.resize(count);
      for (std::size_t k = 0; k < count; ++k)
        keep_[k] = !(nodeVisible(run, 0, slot, k) && nodeVisible(run, 1, slot, k));
      // A member keeps a node: not fully visible in one pass means some node was not.
      if (frontier_.retain(o, keep_) > 0) subset.push_back(o);
    }
    if (subset.size() < 2) {
      for (ObjectId o : subset) frontier_.clear(o);
      continue;
    }
    std::ranges::sort(subset);
    out.push_back(std::move(subset));
  }
  for (std::uint32_t slot = 0; slot < n; ++slot)
    if (run.cis.setOf(slot) == CisConstruction::kNone ||
        run.cis.sets()[run.cis.setOf(slot)].size() < 2)
      frontier_.clear(run.objects[slot]);
}

CullingResult HierarchicalCollisionIndependentSets::cull(const FrameInput& frame) {
  const VisibilityCounters before = backend_->counters();
  CullingResult result;
  stats_ = {};
  ++frameCount_;
  const std::size_t objectCount = scene_->objectCount();
  if (objectCount < 2) return result;  // an object alone collides with nothing

  backend_->setPoses(frame.poses);
  bounds_.update(frame.poses);
  frontier_.reset();
  const auto rootCentre = [&](std::size_t o) {
    return frame.poses[o].apply(frontier_.tree(static_cast<ObjectId>(o)).nodes()[0].box.center);
  };
  int axis = config_.firstAxis.value_or(axisOfLargestSpread(scene_->objectCount(), rootCentre));

  std::vector<std::vector<ObjectId>> work(1);
  for (ObjectId o = 0; o < objectCount; ++o) work[0].push_back(o);
  std::vector<std::vector<ObjectId>> produced;
  for (std::uint32_t level = 0; !work.empty(); ++level, axis = (axis + 1) % 3) {
    stats_.axes.push_back(axis);
    LevelCounters counters{.level = level};
    const std::uint64_t queriesBefore = backend_->counters().queries;
    if (runs_.size() < work.size()) runs_.resize(work.size());
    const std::span<SetRun> runs(runs_.data(), work.size());
    for (std::size_t s = 0; s < work.size(); ++s) {
      runs[s].objects = std::move(work[s]);
      for (ObjectId o : runs[s].objects) counters.nodesTested += frontier_.nodes(o).size();
      drawSet(runs[s], level, axis, frame.poses);
    }
    backend_->fetchResults(visible_);  // one synchronisation per level

    produced.clear();
    for (SetRun& run : runs) splitSet(run, produced);
    work.clear();
    for (auto& set : produced) {
      for (ObjectId o : set) counters.nodesKept += frontier_.nodes(o).size();
      if (std::ranges::all_of(set, [&](ObjectId o) { return frontier_.allLeaves(o); })) {
        PotentiallyCollidingSet out;
        for (ObjectId o : set) {
          result.counters.pcsTriangles += frontier_.triangleCount(o);
          out.members.push_back(frontier_.member(o));
        }
        result.counters.pcsSize += set.size();
        result.sets.push_back(std::move(out));
      } else {
        for (ObjectId o : set) frontier_.expand(o);
        work.push_back(std::move(set));
      }
    }
    counters.sets = produced.size();
    counters.queries = backend_->counters().queries - queriesBefore;
    result.counters.levels.push_back(counters);
  }

  // Lists of sets that did not recur this frame are gone for good or will be rebuilt anyway.
  std::erase_if(lists_, [&](const auto& entry) { return entry.second.lastFrame != frameCount_; });
  result.counters.sets = result.sets.size();
  result.counters.visibility = backend_->counters() - before;
  return result;
}

}  // namespace cdb
