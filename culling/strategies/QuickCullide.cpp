#include "culling/strategies/QuickCullide.h"

#include <algorithm>
#include <array>
#include <iterator>
#include <numeric>

namespace cdb {

QuickCullide::QuickCullide(const DetectorOptions& options) : options_(options) {}

void QuickCullide::attach(const SceneGeometry& scene, VisibilityBackend& backend) {
  scene_ = &scene;
  backend_ = &backend;
  bounds_.attach(scene);
  positionOf_.assign(scene.objectCount(), 0);
}

// Pair (a, b), a before b: b fully visible in pass 1 saw every object before it, a in pass 2 every
// object after it; either one proves the pair free. An object left in no pair touches nothing
// still drawn and leaves the passes, as CULLIDE's pruned objects do.
void QuickCullide::classifyObjects(const Eigen::Vector3d& axis, bool firstAxis) {
  if (objects_.size() < 2 || (!firstAxis && objectPairs_.empty())) {
    objects_.clear();
    objectPairs_.clear();
    return;
  }
  const ViewSpec view{axis, bounds_.unionOf(objects_), options_.resolution};
  // Pass 1's answer is read only of an object that is the later one of a pair, pass 2's only of
  // the earlier one: each pass tests only those (before the first axis every pair is a candidate,
  // so every object but the first in pass 1 and the last in pass 2).
  const std::size_t n = objects_.size();
  std::vector<std::uint8_t> later(n, firstAxis ? 1 : 0), earlier(n, firstAxis ? 1 : 0);
  if (firstAxis) {
    later[0] = 0, earlier[n - 1] = 0;
  } else {
    for (std::uint32_t i = 0; i < n; ++i) positionOf_[objects_[i]] = i;
    for (const ObjectPair& p : objectPairs_)
      earlier[positionOf_[p.a]] = later[positionOf_[p.b]] = 1;
  }
  const auto wholeOf = [&](std::size_t i) { return wholeMesh(*scene_, objects_[i]); };
  issueTwoPasses(
      *backend_, PassPair::fresh(view), n,
      [&](Pass pass, std::size_t i) {
        const bool read = pass == Pass::First ? later[i] : earlier[i];
        return read ? backend_->queryRange(wholeOf(i)) : kNoQuery;
      },
      [&](std::size_t i) { backend_->writeRange(wholeOf(i)); }, answers_.queries, answers_.fetched);
  // (An answer not asked for is never read: it stands at 1.)
  const auto answerOf = [&](QueryIndex q) -> std::uint8_t {
    return q == kNoQuery ? 1 : answers_.fetched[q];
  };
  answers_.first.resize(n);
  answers_.second.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    answers_.first[i] = answerOf(answers_.queries.first[i]);
    answers_.second[i] = answerOf(answers_.queries.second[i]);
  }
  if (firstAxis) {
    // Every pair is a candidate before the first axis: list those it leaves, in pass-1 order.
    objectPairs_.clear();
    for (std::size_t i = 0; i < objects_.size(); ++i)
      if (!answers_.second[i])
        for (std::size_t j = i + 1; j < objects_.size(); ++j)
          if (!answers_.first[j]) objectPairs_.push_back({objects_[i], objects_[j]});
  } else {
    std::erase_if(objectPairs_, [&](const ObjectPair& p) {
      return answers_.first[positionOf_[p.b]] || answers_.second[positionOf_[p.a]];
    });
  }

  objects_.clear();
  for (const auto& p : objectPairs_) {
    objects_.push_back(p.a);
    objects_.push_back(p.b);
  }
  std::sort(objects_.begin(), objects_.end());
  objects_.erase(std::unique(objects_.begin(), objects_.end()), objects_.end());
}

std::vector<SetMember> QuickCullide::drawnTriangles() const {
  std::vector<SetMember> drawn(members_.size());
  for (std::size_t i = 0; i < members_.size(); ++i) {
    const Member& m = members_[i];
    drawn[i].object = m.object;
    const Side* sides[2] = {isEarlier_[i] ? &m.towardLater : nullptr,
                            isLater_[i] ? &m.towardEarlier : nullptr};
    auto& out = drawn[i].triangles;
    if ((sides[0] && sides[0]->all) || (sides[1] && sides[1]->all)) {
      // every triangle: no list
    } else if (sides[0] && sides[1]) {
      std::set_union(sides[0]->triangles.begin(), sides[0]->triangles.end(),
                     sides[1]->triangles.begin(), sides[1]->triangles.end(),
                     std::back_inserter(out));
    } else {
      out = (sides[0] ? sides[0] : sides[1])->triangles;
    }
  }
  return drawn;
}

void QuickCullide::dropEmptyPairsAndMembers() {
  std::erase_if(memberPairs_, [&](const auto& p) {
    const Side& a = members_[p.first].towardLater;
    const Side& b = members_[p.second].towardEarlier;
    return (!a.all && a.triangles.empty()) || (!b.all && b.triangles.empty());
  });
  std::vector<std::uint8_t> earlier(members_.size(), 0), later(members_.size(), 0);
  for (const auto& p : memberPairs_) earlier[p.first] = later[p.second] = 1;
  std::vector<std::uint32_t> renumbered(members_.size(), 0);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < members_.size(); ++i) {
    if (!earlier[i] && !later[i]) continue;
    renumbered[i] = static_cast<std::uint32_t>(kept);
    isEarlier_[kept] = earlier[i];
    isLater_[kept] = later[i];
    if (kept != i) members_[kept] = std::move(members_[i]);  // never onto itself: that empties it
    ++kept;
  }
  members_.resize(kept);
  isEarlier_.resize(kept);
  isLater_.resize(kept);
  for (auto& p : memberPairs_) p = {renumbered[p.first], renumbered[p.second]};
}

// The same rule per triangle: for members A before B, a triangle of A fully visible in pass 2 saw
// all of B drawn and meets none of B's side, and a triangle of B fully visible in pass 1 none of
// A's. So a member's side toward later members loses its triangles fully visible in pass 2, its
// side toward earlier members those fully visible in pass 1. Both passes draw every triangle of
// every side, but each tests only the side it clears: pass 1 a member's side toward earlier
// members, pass 2 its side toward later ones (the other answers would never be read).
void QuickCullide::classifyTriangles(const Eigen::Vector3d& axis) {
  if (memberPairs_.empty()) return;
  const std::vector<SetMember> drawn = drawnTriangles();
  std::vector<ObjectId> objects(members_.size());
  for (std::size_t i = 0; i < members_.size(); ++i) objects[i] = members_[i].object;
  const ViewSpec view{axis, bounds_.unionOf(objects), options_.resolution};

  const auto testSide = [&](std::size_t i, const Side& side) {
    const ObjectId o = members_[i].object;
    return side.all ? backend_->queryTriangles(wholeMesh(*scene_, o))
                    : backend_->queryTriangles(o, side.triangles);
  };
  issueTwoPasses(
      *backend_, PassPair::fresh(view), members_.size(),
      [&](Pass pass, std::size_t i) {
        const Member& m = members_[i];
        if (pass == Pass::First) return isLater_[i] ? testSide(i, m.towardEarlier) : kNoQuery;
        return isEarlier_[i] ? testSide(i, m.towardLater) : kNoQuery;
      },
      [&](std::size_t i) { writeMemberTriangles(*backend_, *scene_, drawn[i]); }, answers_.queries,
      answers_.fetched);
  const std::vector<std::uint8_t>& visible = answers_.fetched;

  // A side keeps its triangles not fully visible in its pass (answers from `first`, in its order).
  const auto narrow = [&](Side& side, std::size_t meshTriangles, QueryIndex first) {
    if (first == kNoQuery) return;
    const std::uint8_t* answer = visible.data() + first;
    if (side.all) {
      for (std::uint32_t t = 0; t < meshTriangles; ++t)
        if (!answer[t]) side.triangles.push_back(t);
      side.all = side.triangles.size() == meshTriangles;
      if (side.all) side.triangles.clear();
      return;
    }
    std::size_t kept = 0;
    for (std::size_t k = 0; k < side.triangles.size(); ++k)
      if (!answer[k]) side.triangles[kept++] = side.triangles[k];
    side.triangles.resize(kept);
  };
  for (std::size_t i = 0; i < members_.size(); ++i) {
    const std::size_t meshTriangles = scene_->meshOf(members_[i].object).triangleCount();
    if (isEarlier_[i]) narrow(members_[i].towardLater, meshTriangles, answers_.queries.second[i]);
    if (isLater_[i]) narrow(members_[i].towardEarlier, meshTriangles, answers_.queries.first[i]);
  }
  dropEmptyPairsAndMembers();
}

CullingResult QuickCullide::result(const VisibilityCounters& work) const {
  CullingResult out;
  out.counters.visibility = work;
  if (memberPairs_.empty()) return out;

  const std::vector<SetMember> drawn = drawnTriangles();
  PotentiallyCollidingSet set;
  set.members.reserve(members_.size());
  // Per member, its side's triangles as positions in its own list (empty: all of them).
  std::vector<std::vector<std::uint32_t>> laterPositions(members_.size()),
      earlierPositions(members_.size());
  std::vector<std::uint32_t> positionIn;
  const auto positions = [&](const Side& side, std::size_t drawnCount,
                             std::vector<std::uint32_t>& list) {
    if (side.all || side.triangles.size() == drawnCount) return;  // every triangle of the member
    list.reserve(side.triangles.size());
    for (std::uint32_t t : side.triangles) list.push_back(positionIn[t]);
  };
  for (std::size_t i = 0; i < members_.size(); ++i) {
    SetMember m = drawn[i];
    const std::size_t drawnCount = memberTriangleCount(*scene_, m);
    out.counters.pcsTriangles += drawnCount;
    positionIn.assign(scene_->meshOf(m.object).triangleCount(), 0);
    if (m.allTriangles())
      std::iota(positionIn.begin(), positionIn.end(), 0u);
    else
      for (std::uint32_t k = 0; k < m.triangles.size(); ++k) positionIn[m.triangles[k]] = k;
    if (isEarlier_[i]) positions(members_[i].towardLater, drawnCount, laterPositions[i]);
    if (isLater_[i]) positions(members_[i].towardEarlier, drawnCount, earlierPositions[i]);
    if (m.triangles.size() == positionIn.size()) m.triangles.clear();
    set.members.push_back(std::move(m));
  }
  set.pairs.emplace();
  set.pairs->reserve(memberPairs_.size());
  for (const auto& [a, b] : memberPairs_)
    set.pairs->push_back({a, b, laterPositions[a], earlierPositions[b]});

  out.counters.pcsSize = set.members.size();
  out.counters.sets = 1;
  out.sets.push_back(std::move(set));
  return out;
}

CullingResult QuickCullide::cull(const FrameInput& frame) {
  const VisibilityCounters before = backend_->counters();
  backend_->setPoses(frame.poses);
  bounds_.update(frame.poses);

  objects_.resize(scene_->objectCount());
  for (std::size_t o = 0; o < objects_.size(); ++o) objects_[o] = static_cast<ObjectId>(o);
  for (std::size_t k = 0; k < kCullideAxes.size(); ++k) classifyObjects(kCullideAxes[k], k == 0);

  // Object pairs into member pairs: members in pass-1 order, every triangle on both sides.
  members_.clear();
  for (std::uint32_t i = 0; i < objects_.size(); ++i) {
    members_.push_back({objects_[i], {}, {}});
    positionOf_[objects_[i]] = i;
  }
  memberPairs_.clear();
  for (const auto& p : objectPairs_) memberPairs_.emplace_back(positionOf_[p.a], positionOf_[p.b]);
  isEarlier_.assign(members_.size(), 0);
  isLater_.assign(members_.size(), 0);
  for (const auto& p : memberPairs_) isEarlier_[p.first] = isLater_[p.second] = 1;
  for (const auto& axis : kCullideAxes) classifyTriangles(axis);

  return result(backend_->counters() - before);
}

}  // namespace cdb
