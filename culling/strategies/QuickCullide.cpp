#include "culling/strategies/QuickCullide.h"

#include <algorithm>
#include <array>

namespace cdb {

namespace {

const std::array<Eigen::Vector3d, 3> kAxes = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                              Eigen::Vector3d::UnitZ()};

constexpr std::uint8_t kVisibleFirst = 1;
constexpr std::uint8_t kVisibleSecond = 2;

}  // namespace

QuickCullide::QuickCullide(const StrategyOptions& options) : options_(options) {}

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
  objectPassAnswers(*backend_, *scene_, objects_, PassPair::fresh(view), answers_);
  if (firstAxis) {
    // Every pair is a candidate before the first axis: list those it leaves, in pass-1 order.
    objectPairs_.clear();
    for (std::size_t i = 0; i < objects_.size(); ++i)
      if (!answers_.second[i])
        for (std::size_t j = i + 1; j < objects_.size(); ++j)
          if (!answers_.first[j]) objectPairs_.push_back({objects_[i], objects_[j]});
  } else {
    for (std::uint32_t i = 0; i < objects_.size(); ++i) positionOf_[objects_[i]] = i;
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
  std::vector<std::vector<std::uint8_t>> marked(members_.size());
  std::vector<std::uint8_t> whole(members_.size(), 0);
  const auto mark = [&](std::uint32_t member, const Side& side) {
    if (side.all) {
      whole[member] = 1;
      return;
    }
    auto& m = marked[member];
    if (m.empty()) m.assign(scene_->meshOf(members_[member]).triangleCount(), 0);
    for (std::uint32_t t : side.triangles) m[t] = 1;
  };
  for (const auto& p : trianglePairs_) {
    mark(p.first, p.firstSide);
    mark(p.second, p.secondSide);
  }
  std::vector<SetMember> drawn(members_.size());
  for (std::size_t i = 0; i < members_.size(); ++i) {
    drawn[i].object = members_[i];
    const auto count = static_cast<std::uint32_t>(scene_->meshOf(members_[i]).triangleCount());
    for (std::uint32_t t = 0; t < count; ++t)
      if (whole[i] || (!marked[i].empty() && marked[i][t])) drawn[i].triangles.push_back(t);
  }
  return drawn;
}

void QuickCullide::dropUnpairedMembers() {
  std::vector<std::uint32_t> renumbered(members_.size(), 0);
  std::vector<std::uint8_t> paired(members_.size(), 0);
  for (const auto& p : trianglePairs_) paired[p.first] = paired[p.second] = 1;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < members_.size(); ++i) {
    if (!paired[i]) continue;
    renumbered[i] = static_cast<std::uint32_t>(kept);
    members_[kept++] = members_[i];
  }
  members_.resize(kept);
  for (auto& p : trianglePairs_) {
    p.first = renumbered[p.first];
    p.second = renumbered[p.second];
  }
}

// The same rule per triangle: for members A before B, a triangle of A fully visible in pass 2 saw
// all of B drawn and meets none of B's side, and a triangle of B fully visible in pass 1 none of
// A's. Each side keeps only the triangles that the other side's passes did not clear.
void QuickCullide::classifyTriangles(const Eigen::Vector3d& axis) {
  if (trianglePairs_.empty()) return;
  const std::vector<SetMember> drawn = drawnTriangles();
  const ViewSpec view{axis, bounds_.unionOf(members_), options_.resolution};
  trianglePassAnswers(*backend_, *scene_, drawn, PassPair::fresh(view), answers_);

  answersBase_.resize(members_.size());
  std::size_t size = 0;
  for (std::size_t i = 0; i < members_.size(); ++i) {
    answersBase_[i] = size;
    size += scene_->meshOf(members_[i]).triangleCount();
  }
  triangleAnswers_.assign(size, 0);
  std::size_t piece = 0;
  for (std::size_t i = 0; i < drawn.size(); ++i)
    for (std::uint32_t t : drawn[i].triangles) {
      triangleAnswers_[answersBase_[i] + t] =
          (answers_.first[piece] ? kVisibleFirst : 0) | (answers_.second[piece] ? kVisibleSecond : 0);
      ++piece;
    }

  // Keeps the side's triangles without `cleared`; false when none is left.
  const auto narrow = [&](Side& side, std::uint32_t member, std::uint8_t cleared) {
    const std::uint8_t* flags = triangleAnswers_.data() + answersBase_[member];
    std::vector<std::uint32_t> kept;
    if (side.all) {
      const auto count = static_cast<std::uint32_t>(scene_->meshOf(members_[member]).triangleCount());
      for (std::uint32_t t = 0; t < count; ++t)
        if (!(flags[t] & cleared)) kept.push_back(t);
      if (kept.size() == count) return true;
    } else {
      for (std::uint32_t t : side.triangles)
        if (!(flags[t] & cleared)) kept.push_back(t);
    }
    side.all = false;
    side.triangles = std::move(kept);
    return !side.triangles.empty();
  };
  std::erase_if(trianglePairs_, [&](TrianglePair& p) {
    const bool firstLeft = narrow(p.firstSide, p.first, kVisibleSecond);
    return !firstLeft || !narrow(p.secondSide, p.second, kVisibleFirst);
  });
  dropUnpairedMembers();
}

CullingResult QuickCullide::result(const VisibilityCounters& work) const {
  CullingResult out;
  out.counters.visibility = work;
  if (trianglePairs_.empty()) return out;

  const std::vector<SetMember> drawn = drawnTriangles();
  PotentiallyCollidingSet set;
  set.members.reserve(members_.size());
  // Per member, a mesh triangle's position in the member's list (members keeping a subset).
  std::vector<std::vector<std::uint32_t>> positionIn(members_.size());
  for (std::size_t i = 0; i < members_.size(); ++i) {
    SetMember m = drawn[i];
    out.counters.pcsTriangles += m.triangles.size();
    if (m.triangles.size() == scene_->meshOf(m.object).triangleCount()) {
      m.triangles.clear();
    } else {
      positionIn[i].assign(scene_->meshOf(m.object).triangleCount(), 0);
      for (std::uint32_t k = 0; k < m.triangles.size(); ++k) positionIn[i][m.triangles[k]] = k;
    }
    set.members.push_back(std::move(m));
  }
  const auto positions = [&](const Side& side, std::uint32_t member) {
    std::vector<std::uint32_t> list;
    if (side.all || side.triangles.size() == drawn[member].triangles.size())
      return list;  // every triangle of the member
    const bool wholeMember = set.members[member].allTriangles();
    list.reserve(side.triangles.size());
    for (std::uint32_t t : side.triangles) list.push_back(wholeMember ? t : positionIn[member][t]);
    return list;
  };
  set.pairs.emplace();
  set.pairs->reserve(trianglePairs_.size());
  for (const auto& p : trianglePairs_)
    set.pairs->push_back({p.first, p.second, positions(p.firstSide, p.first),
                          positions(p.secondSide, p.second)});

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
  for (std::size_t k = 0; k < kAxes.size(); ++k) classifyObjects(kAxes[k], k == 0);

  // Object pairs into member pairs: members in pass-1 order, every triangle on both sides.
  members_ = objects_;
  for (std::uint32_t i = 0; i < members_.size(); ++i) positionOf_[members_[i]] = i;
  trianglePairs_.clear();
  for (const auto& p : objectPairs_)
    trianglePairs_.push_back({positionOf_[p.a], positionOf_[p.b], {}, {}});
  for (const auto& axis : kAxes) classifyTriangles(axis);

  return result(backend_->counters() - before);
}

}  // namespace cdb
