#include "culling/exact/ExactPhase.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <unordered_set>
#include <vector>

#include "core/ArenaForEach.h"
#include "culling/exact/SweepAndPrune.h"
#include "culling/exact/TriangleTriangle.h"

namespace cdb {

namespace {

using Vec3 = Eigen::Vector3d;

// Widens a world box computed through transformAabb by more than the few ulps by which vertices
// transformed one by one may stray outside it, so that no touching pair is pruned by rounding.
Aabb conservative(Aabb box) {
  if (box.isEmpty()) return box;
  const double scale = box.min().cwiseAbs().cwiseMax(box.max().cwiseAbs()).maxCoeff();
  const Vec3 slack = Vec3::Constant(1e-12 * scale + 1e-300);
  box.min() -= slack;
  box.max() += slack;
  return box;
}

// A member's triangles in world space, built the first time the member meets another in a set.
struct MemberGeometry {
  std::vector<Vec3> vertices;
  std::vector<Triangle> ownTriangles;   // used when the mesh's own list does not fit
  std::span<const Triangle> triangles;  // index into `vertices`, one per member triangle
  std::vector<Aabb> boxes;              // world box of each member triangle
  Aabb bounds;                          // their union: tight, unlike the set-level box
};

// Per thread: the candidates of the pair it tests.
struct PairScratch {
  std::vector<Aabb> candidateBoxes[2];
  std::vector<std::uint32_t> candidateTriangles[2];
  std::vector<IndexPair> trianglePairs;
  SweepAndPrune sweep;
};

struct PairOutcome {
  std::uint64_t triangleTests = 0;
  std::uint64_t hits = 0;
};

}  // namespace

struct ExactPhase::Workspace {
  // Per mesh, from the constructor.
  std::vector<Aabb> meshBounds;
  std::vector<std::vector<Aabb>> localTriangleBoxes;

  // Per set and per pair; kept so that frames after the first do not allocate.
  std::vector<Aabb> memberBoxes;
  std::vector<IndexPair> memberPairs;
  std::vector<std::uint32_t> listedPairOf;  // a set with listed pairs: each member pair's entry
  std::vector<MemberGeometry> members;
  SweepAndPrune sweep;
  std::vector<ObjectPair> colliding;
  std::unordered_set<std::uint64_t> collidingKeys;

  // The member pairs of a set to test, in order; whether an earlier one names the same objects
  // (then it is tested after them, in order, as it is skipped once they collide); the members
  // they need; each pair's outcome.
  std::vector<std::uint32_t> toTest;
  std::vector<std::uint8_t> repeats;
  std::unordered_set<std::uint64_t> keysInSet;
  std::vector<std::uint32_t> needed;
  std::vector<std::uint8_t> isNeeded;
  std::vector<PairOutcome> outcomes;

  // Without threads (nullptr) everything runs on the calling thread.
  std::unique_ptr<tbb::task_arena> arena;
  tbb::enumerable_thread_specific<PairScratch> scratch;
};

ExactPhase::ExactPhase(const SceneGeometry& scene, int threads)
    : scene_(scene), work_(std::make_unique<Workspace>()) {
  if (threads < 0)
    throw std::invalid_argument("exact phase: " + std::to_string(threads) + " threads");
  if (threads == 0) threads = tbb::info::default_concurrency();
  if (threads > 1) work_->arena = std::make_unique<tbb::task_arena>(threads);
  work_->meshBounds.reserve(scene.meshes.size());
  work_->localTriangleBoxes.resize(scene.meshes.size());
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    work_->meshBounds.push_back(mesh.bounds());
    auto& boxes = work_->localTriangleBoxes[m];
    boxes.reserve(mesh.triangleCount());
    for (const Triangle& t : mesh.triangles) {
      Aabb box(mesh.vertices[t[0]].cast<double>());
      box.extend(mesh.vertices[t[1]].cast<double>());
      box.extend(mesh.vertices[t[2]].cast<double>());
      boxes.push_back(box);
    }
  }
}

ExactPhase::~ExactPhase() = default;
ExactPhase::ExactPhase(ExactPhase&&) noexcept = default;

namespace {

// Local box of a member's triangles (checking the subset's indices on the way).
Aabb localBoxOf(const SetMember& member, const Aabb& meshBounds,
                const std::vector<Aabb>& triBoxes) {
  if (member.allTriangles()) return meshBounds;
  Aabb box;
  for (std::uint32_t t : member.triangles) {
    if (t >= triBoxes.size())
      throw std::out_of_range("exact phase: triangle " + std::to_string(t) + " of object " +
                              std::to_string(member.object) + " is out of range");
    box.extend(triBoxes[t]);
  }
  return box;
}

// World vertices: the rotation as a matrix, applied in this exact form by the ground truth too,
// so both run the triangle test on bit-identical coordinates.
void transformVertices(const Mesh& mesh, const Pose& pose, std::vector<Vec3>& out) {
  const Eigen::Matrix3d r = pose.rotation.toRotationMatrix();
  out.resize(mesh.vertices.size());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    out[v] = r * mesh.vertices[v].cast<double>() + pose.translation;
}

void prepare(MemberGeometry& g, const Mesh& mesh, const SetMember& member, const Pose& pose) {
  const std::size_t count = member.allTriangles() ? mesh.triangleCount() : member.triangles.size();
  if (member.allTriangles()) {
    transformVertices(mesh, pose, g.vertices);
    g.triangles = mesh.triangles;
  } else if (3 * count >= mesh.vertices.size()) {
    // A large subset: transforming every vertex once is cheaper than three per triangle.
    transformVertices(mesh, pose, g.vertices);
    g.ownTriangles.resize(count);
    for (std::size_t k = 0; k < count; ++k) g.ownTriangles[k] = mesh.triangles[member.triangles[k]];
    g.triangles = g.ownTriangles;
  } else {
    const Eigen::Matrix3d r = pose.rotation.toRotationMatrix();
    g.vertices.resize(3 * count);
    g.ownTriangles.resize(count);
    for (std::size_t k = 0; k < count; ++k) {
      const Triangle& t = mesh.triangles[member.triangles[k]];
      for (int c = 0; c < 3; ++c)
        g.vertices[3 * k + c] = r * mesh.vertices[t[c]].cast<double>() + pose.translation;
      const auto base = std::uint32_t(3 * k);
      g.ownTriangles[k] = {base, base + 1, base + 2};
    }
    g.triangles = g.ownTriangles;
  }
  g.boxes.resize(count);
  g.bounds.setEmpty();
  for (std::size_t k = 0; k < count; ++k) {
    const Triangle& t = g.triangles[k];
    Aabb box(g.vertices[t[0]]);
    box.extend(g.vertices[t[1]]);
    box.extend(g.vertices[t[2]]);
    g.boxes[k] = box;
    g.bounds.extend(box);
  }
}

// The member triangles (all, or the positions in `subset`) whose world boxes reach into `region`;
// returns the box around them.
Aabb collectCandidates(const MemberGeometry& g, std::span<const std::uint32_t> subset,
                       const Aabb& region, std::vector<Aabb>& boxes,
                       std::vector<std::uint32_t>& triangles) {
  boxes.clear();
  triangles.clear();
  Aabb reach;
  const auto consider = [&](std::uint32_t k) {
    if (g.boxes[k].intersects(region)) {
      boxes.push_back(g.boxes[k]);
      triangles.push_back(k);
      reach.extend(g.boxes[k]);
    }
  };
  if (subset.empty()) {
    for (std::uint32_t k = 0; k < g.boxes.size(); ++k) consider(k);
  } else {
    for (std::uint32_t k : subset) consider(k);
  }
  return reach;
}

// A set's listed pairs whose member boxes overlap, as sweep-and-prune would have found them, into
// `out`; checks the listed indices on the way.
void listedOverlaps(const SceneGeometry& scene, const PotentiallyCollidingSet& set,
                    const std::vector<Aabb>& memberBoxes, std::vector<IndexPair>& out,
                    std::vector<std::uint32_t>& pairOf) {
  out.clear();
  pairOf.clear();
  const auto& members = set.members;
  const auto check = [&](std::span<const std::uint32_t> positions, std::uint32_t member) {
    const SetMember& m = members[member];
    const std::size_t count =
        m.allTriangles() ? scene.meshOf(m.object).triangleCount() : m.triangles.size();
    for (std::uint32_t k : positions)
      if (k >= count)
        throw std::out_of_range("exact phase: pair position " + std::to_string(k) + " beyond the " +
                                std::to_string(count) + " triangles of member " +
                                std::to_string(member));
  };
  for (std::uint32_t p = 0; p < set.pairs->size(); ++p) {
    const MemberPair& pair = (*set.pairs)[p];
    if (pair.first >= members.size() || pair.second >= members.size())
      throw std::out_of_range("exact phase: pair " + std::to_string(p) + " names member " +
                              std::to_string(std::max(pair.first, pair.second)) + " of " +
                              std::to_string(members.size()));
    check(pair.firstTriangles, pair.first);
    check(pair.secondTriangles, pair.second);
    if (!memberBoxes[pair.first].intersects(memberBoxes[pair.second])) continue;
    out.push_back({pair.first, pair.second});
    pairOf.push_back(p);
  }
}

// Keeps the candidates whose boxes reach into `region`, in place; returns the box around them.
Aabb narrowCandidates(const Aabb& region, std::vector<Aabb>& boxes,
                      std::vector<std::uint32_t>& triangles) {
  std::size_t kept = 0;
  Aabb reach;
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    if (boxes[k].intersects(region)) {
      reach.extend(boxes[k]);
      boxes[kept] = boxes[k];
      triangles[kept++] = triangles[k];
    }
  }
  boxes.resize(kept);
  triangles.resize(kept);
  return reach;
}

std::uint64_t keyOf(ObjectPair p) { return (std::uint64_t(p.a) << 32) | p.b; }

// Tests a member pair's triangles: only triangles inside both members' tight world boxes can
// meet. Narrowing once more to the box around the other side's candidates is cheap and often
// shrinks both sides.
PairOutcome testPair(const MemberGeometry& ga, std::span<const std::uint32_t> subsetA,
                     const MemberGeometry& gb, std::span<const std::uint32_t> subsetB,
                     PairScratch& s) {
  PairOutcome out;
  const Aabb common = ga.bounds.intersection(gb.bounds);
  if (common.isEmpty()) return out;
  const Aabb reachA =
      collectCandidates(ga, subsetA, common, s.candidateBoxes[0], s.candidateTriangles[0]);
  if (s.candidateBoxes[0].empty()) return out;
  const Aabb reachB =
      collectCandidates(gb, subsetB, reachA, s.candidateBoxes[1], s.candidateTriangles[1]);
  if (s.candidateBoxes[1].empty()) return out;
  narrowCandidates(reachB, s.candidateBoxes[0], s.candidateTriangles[0]);
  s.sweep.overlaps(s.candidateBoxes[0], s.candidateBoxes[1], s.trianglePairs);
  for (const IndexPair& tp : s.trianglePairs) {
    const Triangle& ta = ga.triangles[s.candidateTriangles[0][tp.i]];
    const Triangle& tb = gb.triangles[s.candidateTriangles[1][tp.j]];
    out.hits += trianglesIntersect(ga.vertices[ta[0]], ga.vertices[ta[1]], ga.vertices[ta[2]],
                                   gb.vertices[tb[0]], gb.vertices[tb[1]], gb.vertices[tb[2]]);
  }
  out.triangleTests = s.trianglePairs.size();
  return out;
}

}  // namespace

CollisionReport ExactPhase::run(std::span<const Pose> poses, const PotentiallyCollidingSets& sets) {
  if (poses.size() < scene_.objectCount())
    throw std::invalid_argument("exact phase: " + std::to_string(poses.size()) + " poses for " +
                                std::to_string(scene_.objectCount()) + " objects");
  Workspace& w = *work_;
  CollisionReport report;
  w.colliding.clear();
  w.collidingKeys.clear();
  const bool severalSets = sets.size() > 1;

  for (const PotentiallyCollidingSet& set : sets) {
    const auto& members = set.members;
    if (members.size() < 2) continue;

    w.memberBoxes.clear();
    for (const SetMember& m : members) {
      const std::uint32_t mesh = scene_.objects.at(m.object).mesh;
      const Aabb local = localBoxOf(m, w.meshBounds[mesh], w.localTriangleBoxes[mesh]);
      w.memberBoxes.push_back(conservative(transformAabb(local, poses[m.object])));
    }
    if (set.pairs)
      listedOverlaps(scene_, set, w.memberBoxes, w.memberPairs, w.listedPairOf);
    else
      w.sweep.overlaps(w.memberBoxes, w.memberPairs);

    if (w.members.size() < members.size()) w.members.resize(members.size());

    // The pairs to test. Once a pair of objects collides, later sets skip it, and so do later
    // pairs of this set that name the same objects (members may share an object): those repeats
    // are tested after the others, in order, so that what is counted does not depend on threads.
    w.toTest.clear();
    w.repeats.clear();
    w.keysInSet.clear();
    w.isNeeded.assign(members.size(), 0);
    w.needed.clear();
    for (std::uint32_t q = 0; q < w.memberPairs.size(); ++q) {
      const IndexPair& mp = w.memberPairs[q];
      if (members[mp.i].object == members[mp.j].object) continue;
      const std::uint64_t key = keyOf(ObjectPair::of(members[mp.i].object, members[mp.j].object));
      if (severalSets && w.collidingKeys.contains(key)) continue;
      w.toTest.push_back(q);
      w.repeats.push_back(severalSets && !w.keysInSet.insert(key).second);
      for (const std::uint32_t m : {mp.i, mp.j})
        if (!w.isNeeded[m]) w.isNeeded[m] = 1, w.needed.push_back(m);
    }
    forEachIndex(w.arena.get(), w.needed.size(), [&](std::size_t k) {
      const SetMember& m = members[w.needed[k]];
      prepare(w.members[w.needed[k]], scene_.meshOf(m.object), m, poses[m.object]);
    });
    const auto test = [&](std::size_t k) {
      const std::uint32_t q = w.toTest[k];
      const IndexPair& mp = w.memberPairs[q];
      std::span<const std::uint32_t> subsetA, subsetB;  // empty: every triangle of the member
      if (set.pairs) {
        const MemberPair& listed = (*set.pairs)[w.listedPairOf[q]];
        subsetA = listed.firstTriangles;
        subsetB = listed.secondTriangles;
      }
      return testPair(w.members[mp.i], subsetA, w.members[mp.j], subsetB, w.scratch.local());
    };
    w.outcomes.resize(w.toTest.size());
    forEachIndex(w.arena.get(), w.toTest.size(), [&](std::size_t k) {
      if (!w.repeats[k]) w.outcomes[k] = test(k);
    });

    for (std::size_t k = 0; k < w.toTest.size(); ++k) {
      const IndexPair& mp = w.memberPairs[w.toTest[k]];
      const ObjectPair objects = ObjectPair::of(members[mp.i].object, members[mp.j].object);
      if (w.repeats[k]) {
        if (w.collidingKeys.contains(keyOf(objects))) continue;
        w.outcomes[k] = test(k);
      }
      const PairOutcome& outcome = w.outcomes[k];
      ++report.pairsTested;
      report.triangleTests += outcome.triangleTests;
      if (outcome.hits == 0) continue;
      report.collidingTrianglePairs += outcome.hits;
      w.colliding.push_back(objects);
      if (severalSets) w.collidingKeys.insert(keyOf(objects));
    }
  }

  std::sort(w.colliding.begin(), w.colliding.end());
  w.colliding.erase(std::unique(w.colliding.begin(), w.colliding.end()), w.colliding.end());
  report.collidingPairs = w.colliding;
  return report;
}

}  // namespace cdb
