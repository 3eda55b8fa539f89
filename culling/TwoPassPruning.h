#pragma once
// CULLIDE's two-pass visibility pruning (thesis 2.4), shared by `cullide` and `sorted`: pass 1
// draws pieces in one order, testing each against those drawn before it; pass 2 draws them in
// the reverse order. A piece fully visible in both passes touches nothing else drawn, and leaves.
// The strategies differ only in the order and in how the two passes use the depth buffer. The
// passes themselves (issueTwoPasses) also serve `quick_cullide` and `cullide_bvh`.
#include <array>
#include <cstdint>
#include <numeric>
#include <type_traits>
#include <vector>

#include "culling/CullingStrategy.h"
#include "culling/PotentiallyCollidingSets.h"
#include "culling/visibility/VisibilityBackend.h"

namespace cdb {

// CULLIDE's view axes, in the order its passes take them: x, y, z.
inline const std::array<Eigen::Vector3d, 3> kCullideAxes = {
    Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};

struct PassPair {
  ViewSpec first, second;
  DepthUse firstDepth = DepthUse::Fresh, secondDepth = DepthUse::Fresh;

  // Both passes along `view`, each with its own clear (CULLIDE).
  static PassPair fresh(const ViewSpec& view) {
    return {view, view, DepthUse::Fresh, DepthUse::Fresh};
  }
  // Pass 2 looks the other way and shares pass 1's clear (depth-sorted culling, thesis 3.2).
  static PassPair shared(const ViewSpec& view) {
    ViewSpec opposite = view;
    opposite.direction = -view.direction;
    return {view, opposite, DepthUse::SharedFirst, DepthUse::SharedSecond};
  }
};

// Where each piece's answers begin in the fetched answers, per pass (kNoQuery: the pass asked
// nothing of it).
struct PassQueries {
  std::vector<QueryIndex> first;
  std::vector<QueryIndex> second;
};

// Both passes' answers, one per piece in pass-1 order. `first`: fully visible with respect to the
// pieces before it (pass 1); `second`: fully visible with respect to the pieces after it (pass 2).
// By CULLIDE's lemma a piece fully visible with respect to a set collides with none of it.
struct TwoPassAnswers {
  std::vector<std::uint8_t> first;
  std::vector<std::uint8_t> second;
  std::vector<std::uint8_t> fetched;  // the backend's answers in issue order, reused across calls
  PassQueries queries;                // where each piece's answers begin (a scratch)
  [[nodiscard]] bool inBoth(std::size_t piece) const { return first[piece] && second[piece]; }
};

// Which pass a piece is tested in (issueTwoPasses' `test`).
enum class Pass { First, Second };

// A piece's pass-2 test not gated (issueTwoPasses' `gated`).
inline constexpr auto kNotGated = [](std::size_t) { return std::uint32_t{0}; };

// CULLIDE's two passes over pieces 0 .. n - 1 (`n`, pass 1's draw order), both issued before one
// fetch into `fetched`: pass 1 in order, pass 2 in reverse, each piece tested first and then
// written, so that it is tested against the pieces before it (pass 1) or after it (pass 2) and
// never against itself. `test(pass, i)` issues piece i's test in that pass and returns its first
// answer (kNoQuery: none asked, queries.first or queries.second says so); `write(i)` draws it.
// `gated(i)`: how many answers of piece i's pass-2 test are gated by its pass-1 test
// (VisibilityBackend::gateAnswers; 0 for none, as kNotGated says for every piece).
template <class Test, class Write, class Gated = std::remove_const_t<decltype(kNotGated)>>
void issueTwoPasses(VisibilityBackend& backend, const PassPair& passes, std::size_t n, Test&& test,
                    Write&& write, PassQueries& queries, std::vector<std::uint8_t>& fetched,
                    Gated gated = kNotGated) {
  queries.first.assign(n, kNoQuery);
  queries.second.assign(n, kNoQuery);
  backend.beginPass(passes.first, passes.firstDepth);
  for (std::size_t i = 0; i < n; ++i) {
    queries.first[i] = test(Pass::First, i);
    write(i);
  }
  backend.beginPass(passes.second, passes.secondDepth);
  for (std::size_t i = n; i-- > 0;) {
    queries.second[i] = test(Pass::Second, i);
    const std::uint32_t count = gated(i);
    if (count > 0 && queries.first[i] != kNoQuery && queries.second[i] != kNoQuery)
      backend.gateAnswers(queries.second[i], queries.first[i], count);
    write(i);
  }
  backend.fetchResults(fetched);
}

// What a strategy reads of the two passes: each pass' answers on their own (quick_cullide's
// pairs), or only whether a piece is fully visible in both (CULLIDE's pruning). Then each pass-2
// query is gated by the same piece's pass-1 answer (VisibilityBackend::gateAnswers): `second`
// holds "visible in both", and a backend need not test in pass 2 what pass 1 found occluded.
enum class PassAnswersUse { EachPass, InBoth };

// Object level: both passes over `order` (pass 1's draw order), each object queried then drawn
// whole. `answers` is reused across calls.
void objectPassAnswers(VisibilityBackend& backend, const SceneGeometry& scene,
                       const std::vector<ObjectId>& order, const PassPair& passes,
                       TwoPassAnswers& answers, PassAnswersUse use = PassAnswersUse::EachPass);

// Triangle level: one query per triangle, a member's triangles in one batch, then the member
// drawn; `ordered` is pass 1's order, each member with its triangle list or none (every triangle
// of its mesh: drawn as the whole mesh). An object's own triangles are all tested before it is
// drawn, so an object never occludes itself. The answers are per triangle, members after one
// another in pass-1 order, a member's in its list's order (or its mesh's).
void trianglePassAnswers(VisibilityBackend& backend, const SceneGeometry& scene,
                         const std::vector<SetMember>& ordered, const PassPair& passes,
                         TwoPassAnswers& answers, PassAnswersUse use = PassAnswersUse::EachPass);

// CULLIDE's pruning on those answers. Object level: the objects not fully visible in both passes,
// in `order`'s order.
[[nodiscard]] std::vector<ObjectId> pruneObjectsTwoPass(VisibilityBackend& backend,
                                                        const SceneGeometry& scene,
                                                        const std::vector<ObjectId>& order,
                                                        const PassPair& passes,
                                                        TwoPassAnswers& answers);

// Triangle level, `ordered` consumed: the members with the triangles left, in pass-1 order,
// dropping members left with none (a member of every triangle that keeps them all keeps no list).
[[nodiscard]] std::vector<SetMember> pruneTrianglesTwoPass(VisibilityBackend& backend,
                                                           const SceneGeometry& scene,
                                                           std::vector<SetMember> ordered,
                                                           const PassPair& passes,
                                                           TwoPassAnswers& answers);

// The objects as members of every triangle (no list), for the triangle level.
[[nodiscard]] std::vector<SetMember> withAllTriangles(const std::vector<ObjectId>& objects);

// How many triangles a member has: its list's, or its mesh's when it has every triangle.
[[nodiscard]] std::size_t memberTriangleCount(const SceneGeometry& scene, const SetMember& m);

// A member's triangles as one batch (an answer per triangle, in its list's order or its mesh's),
// and its triangles written (as the whole mesh where it has them all).
QueryIndex queryMemberTriangles(VisibilityBackend& backend, const SceneGeometry& scene,
                                const SetMember& m);
void writeMemberTriangles(VisibilityBackend& backend, const SceneGeometry& scene,
                          const SetMember& m);

// Appends to `kept` member `m` (consumed) with the triangles whose piece `keep` accepts (pieces
// first, first + 1, ..., one per triangle as memberTriangleCount counts them): nothing when it
// keeps none, no list when a member of every triangle keeps them all. A list is narrowed in place
// (the triangle level's lists keep their memory from axis to axis). Returns how many pieces were
// the member's.
template <class Keep>
std::size_t keepTriangles(const SceneGeometry& scene, SetMember&& m, std::size_t first, Keep&& keep,
                          std::vector<SetMember>& kept) {
  if (m.allTriangles()) {
    const auto n = static_cast<std::uint32_t>(scene.meshOf(m.object).triangleCount());
    std::uint32_t count = 0;
    for (std::uint32_t t = 0; t < n; ++t) count += keep(first + t) ? 1u : 0u;
    if (count == 0) return n;
    if (count < n) {  // (all of them: no list)
      m.triangles.reserve(count);
      for (std::uint32_t t = 0; t < n; ++t)
        if (keep(first + t)) m.triangles.push_back(t);
    }
    kept.push_back(std::move(m));
    return n;
  }
  const std::size_t n = m.triangles.size();
  std::size_t out = 0;
  for (std::size_t k = 0; k < n; ++k)
    if (keep(first + k)) m.triangles[out++] = m.triangles[k];
  if (out == 0) return n;
  m.triangles.resize(out);
  kept.push_back(std::move(m));
  return n;
}

// CULLIDE's two levels along its three axes: every object pruned along each axis in turn
// (`pruneObjects(pcs, axis)`), then the triangles of the objects left (`pruneTriangles(members,
// axis)`); returns the members left. The strategy's passes are what the two callables draw.
template <class PruneObjects, class PruneTriangles>
[[nodiscard]] std::vector<SetMember> pruneCullideLevels(const SceneGeometry& scene,
                                                        PruneObjects&& pruneObjects,
                                                        PruneTriangles&& pruneTriangles) {
  std::vector<ObjectId> pcs(scene.objectCount());
  std::iota(pcs.begin(), pcs.end(), ObjectId{0});
  for (const auto& axis : kCullideAxes) pruneObjects(pcs, axis);
  std::vector<SetMember> members = withAllTriangles(pcs);
  for (const auto& axis : kCullideAxes) pruneTriangles(members, axis);
  return members;
}

// The one potentially colliding set the triangle level leaves (none when it is empty), with its
// counters; members keeping every triangle get the empty "all triangles" list.
[[nodiscard]] CullingResult singleSetResult(const SceneGeometry& scene,
                                            std::vector<SetMember> members,
                                            const VisibilityCounters& work);

}  // namespace cdb
