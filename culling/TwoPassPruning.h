#pragma once
// CULLIDE's two-pass visibility pruning (thesis 2.4), shared by `cullide` and `sorted`: pass 1
// draws pieces in one order, testing each against those drawn before it; pass 2 draws them in
// the reverse order. A piece fully visible in both passes touches nothing else drawn, and leaves.
// The strategies differ only in the order and in how the two passes use the depth buffer.
#include <cstdint>
#include <vector>

#include "culling/CullingStrategy.h"
#include "culling/PotentiallyCollidingSets.h"
#include "culling/visibility/VisibilityBackend.h"

namespace cdb {

struct PassPair {
  ViewSpec first, second;
  DepthUse firstDepth = DepthUse::Fresh, secondDepth = DepthUse::Fresh;

  // Both passes along `view`, each with its own clear (CULLIDE).
  static PassPair fresh(const ViewSpec& view) { return {view, view, DepthUse::Fresh, DepthUse::Fresh}; }
  // Pass 2 looks the other way and shares pass 1's clear (depth-sorted culling, thesis 3.2).
  static PassPair shared(const ViewSpec& view) {
    ViewSpec opposite = view;
    opposite.direction = -view.direction;
    return {view, opposite, DepthUse::SharedFirst, DepthUse::SharedSecond};
  }
};

// Object level: `order` is pass 1's draw order. Returns the objects not fully visible in both
// passes, in that order. `answers` is scratch space reused across calls.
[[nodiscard]] std::vector<ObjectId> pruneObjectsTwoPass(VisibilityBackend& backend,
                                                        const SceneGeometry& scene,
                                                        const std::vector<ObjectId>& order,
                                                        const PassPair& passes,
                                                        std::vector<std::uint8_t>& answers);

// Triangle level: one query per triangle, a member's triangles in one batch; `ordered` (pass 1's order, triangle lists explicit) is
// consumed. An object's own triangles are all tested before it is drawn, so an object never
// occludes itself. Returns the members with the triangles left, in pass-1 order, dropping members
// left with none.
[[nodiscard]] std::vector<SetMember> pruneTrianglesTwoPass(VisibilityBackend& backend,
                                                           const SceneGeometry& scene,
                                                           std::vector<SetMember> ordered,
                                                           const PassPair& passes,
                                                           std::vector<std::uint8_t>& answers);

// Each object with its whole triangle list written out, for the triangle level.
[[nodiscard]] std::vector<SetMember> withAllTriangles(const SceneGeometry& scene,
                                                      const std::vector<ObjectId>& objects);

// The one potentially colliding set the triangle level leaves (none when it is empty), with its
// counters; members keeping every triangle get the empty "all triangles" list.
[[nodiscard]] CullingResult singleSetResult(const SceneGeometry& scene, std::vector<SetMember> members,
                                            const VisibilityCounters& work);

}  // namespace cdb
