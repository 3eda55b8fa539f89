#include "culling/strategies/CollisionIndependentSets.h"

#include <algorithm>

// The endpoints of the objects' intervals on the view axis are numbered p = 0 .. 2n-1 far to
// near for the pass-1 view (+axis): e_i is O_i's far end (MAX), b_i its near end (MIN). At equal
// depth an e comes before a b, so touching intervals count as overlapping. The thesis compares
// depths; positions in this list say the same without ties between equal depths.
//
// Pass 1 (far to near; each object queried, then drawn, at its b):
//  - at e_i: PS := max(PS, pos(b_i)), the nearest near end among objects whose far end is
//    passed: how far toward the viewer the objects reached so far extend;
//  - at b_i: O_i is tested against every object of farther Min. If not fully visible it joins
//    ActiveCIS (a new set when there is none), SS := b_i and OV := PS. Then, if ActiveCIS is open
//    and p == OV, ActiveCIS is complete: nothing reached so far extends nearer than here.
// Pass 2 (near to far, looking along -axis, same depth buffer; each object drawn at its b):
//  - a member of a pass-1 set makes its set active. The thesis switches at the set's SS (its
//    nearest member); pass-1 sets occupy disjoint stretches of the list, so any member will do;
//  - an object fully visible in pass 1 is tested against every object of nearer Min and joins
//    ActiveCIS when not fully visible; with no set active it is dropped without a test.
//
// Why objects of different sets, and dropped objects, cannot collide. Fully visible with respect
// to drawn objects means touching none of them (CULLIDE). Let F and N collide, F's Min farther.
// N was tested after F was drawn, so N is not fully visible in pass 1: N is a member. Their
// intervals overlap, so e_N precedes b_F and PS >= pos(b_N) from b_F on. Any insertion at or after
// b_F sets OV >= pos(b_N), and a set completes only at p == OV after that element's insertion, so
// a set that receives a member at or after b_F is still open when N is inserted at b_N:
//  - F is a member: N joins F's set;
//  - F is fully visible in pass 1: let M be the member just nearer than F (N is a candidate, so
//    M exists and pos(b_F) < pos(b_M) <= pos(b_N)); M's set is N's. In pass 2 the set active at
//    b_F is M's, and F, tested after N was drawn, is not fully visible: F joins N's set.
// A dropped object touches nothing farther (pass 1) and nothing nearer: either it was fully
// visible in pass 2, or no member is nearer, while anything nearer touching it would be a member.
// Hence every colliding pair ends in one set, and a set with one member can be dropped.

namespace cdb {

namespace {
MeshRange wholeMesh(const SceneGeometry& scene, ObjectId o) {
  return {o, 0, static_cast<std::uint32_t>(scene.meshOf(o).triangleCount())};
}
constexpr int kNone = -1;
}  // namespace

CollisionIndependentSets::CollisionIndependentSets(const StrategyOptions& options, CisOptions cis)
    : options_(options), cis_(cis) {}

void CollisionIndependentSets::attach(const SceneGeometry& scene, VisibilityBackend& backend) {
  scene_ = &scene;
  backend_ = &backend;
  bounds_.attach(scene);
  allObjects_.resize(scene.objectCount());
  for (std::size_t i = 0; i < allObjects_.size(); ++i) allObjects_[i] = static_cast<ObjectId>(i);
}

int CollisionIndependentSets::chooseAxis() const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Vector3d sumSq = Eigen::Vector3d::Zero();
  for (ObjectId o : allObjects_) {
    const Eigen::Vector3d c = bounds_[o].center();
    sum += c;
    sumSq += c.cwiseProduct(c);
  }
  const double n = static_cast<double>(allObjects_.size());
  const Eigen::Vector3d variance = sumSq / n - (sum / n).cwiseProduct(sum / n);
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (variance[k] > variance[axis]) axis = k;
  return axis;
}

CullingResult CollisionIndependentSets::cull(const FrameInput& frame) {
  const VisibilityCounters before = backend_->counters();
  CullingResult result;
  stats_ = {};
  const std::size_t n = allObjects_.size();
  if (n < 2) return result;  // an object alone collides with nothing

  backend_->setPoses(frame.poses);
  bounds_.update(frame.poses);
  stats_.axis = cis_.axis.value_or(chooseAxis());
  SortedIntervals& sorted = sorted_[stats_.axis];
  stats_.sortExchanges = sorted.update(allObjects_, bounds_, Eigen::Vector3d::Unit(stats_.axis));

  // The list is ascending along +axis, i.e. near to far for the pass-1 view.
  const auto list = sorted.endpoints();
  const std::uint32_t last = static_cast<std::uint32_t>(list.size() - 1);
  auto at = [&](std::uint32_t p) -> const SortedIntervals::Endpoint& { return list[last - p]; };
  auto posOfMin = [&](std::uint32_t slot) { return last - sorted.minIndex(slot); };

  const ViewSpec view{Eigen::Vector3d::Unit(stats_.axis), bounds_.unionOf(allObjects_),
                      options_.resolution};

  // Pass 1: draws do not depend on answers, so every query is issued before the one fetch.
  backend_->beginPass(view, DepthUse::SharedFirst);
  for (std::uint32_t p = 0; p <= last; ++p) {
    if (at(p).isMax) continue;
    backend_->queryRange(wholeMesh(*scene_, at(p).object));
    backend_->writeRange(wholeMesh(*scene_, at(p).object));
  }
  backend_->fetchResults(visible_);

  std::vector<std::vector<ObjectId>> sets;
  std::vector<int> setOf(n, kNone);  // by slot (= object id here)
  {
    int active = kNone;
    std::int64_t ps = -1;  // covers nothing yet (the thesis' +infinity)
    std::int64_t ov = -1;
    std::uint32_t ss = 0;
    std::size_t answer = 0;
    for (std::uint32_t p = 0; p <= last; ++p) {
      const auto& e = at(p);
      if (e.isMax) {
        ps = std::max<std::int64_t>(ps, posOfMin(e.slot));
        continue;
      }
      if (!visible_[answer++]) {
        if (active == kNone) {
          active = static_cast<int>(sets.size());
          sets.emplace_back();
        }
        sets[active].push_back(e.object);
        setOf[e.slot] = active;
        ss = p;
        ov = ps;
      }
      if (active != kNone && ov == p) {
        stats_.separatingSurfaces.push_back(ss);
        active = kNone;
      }
    }
    // Cannot remain open: at every insertion OV >= the current position, since an object's e
    // precedes its b. Closed anyway so a set is never left half recorded.
    if (active != kNone) stats_.separatingSurfaces.push_back(ss);
  }

  // Pass 2: which objects are tested depends only on pass 1, so again one fetch.
  ViewSpec opposite = view;
  opposite.direction = -view.direction;
  backend_->beginPass(opposite, DepthUse::SharedSecond);
  struct Candidate {
    ObjectId object;
    int set;
  };
  std::vector<Candidate> candidates;
  {
    int active = kNone;
    for (std::uint32_t p = last + 1; p-- > 0;) {
      const auto& e = at(p);
      if (e.isMax) continue;
      if (setOf[e.slot] != kNone) {
        active = setOf[e.slot];
      } else if (active != kNone) {
        backend_->queryRange(wholeMesh(*scene_, e.object));
        candidates.push_back({e.object, active});
      } else {
        ++stats_.dropped;
      }
      backend_->writeRange(wholeMesh(*scene_, e.object));
    }
  }
  backend_->fetchResults(visible_);
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    if (visible_[k])
      ++stats_.dropped;
    else
      sets[candidates[k].set].push_back(candidates[k].object);
  }

  for (auto& members : sets) {
    if (members.size() < 2) {
      ++stats_.singletons;
      continue;
    }
    PotentiallyCollidingSet out;
    for (ObjectId o : members) {
      out.members.push_back({o, {}});
      result.counters.pcsTriangles += scene_->meshOf(o).triangleCount();
    }
    result.counters.pcsSize += members.size();
    result.sets.push_back(std::move(out));
  }
  result.counters.sets = result.sets.size();
  result.counters.visibility = backend_->counters() - before;
  return result;
}

}  // namespace cdb
