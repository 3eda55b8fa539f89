#pragma once
// What a culling strategy hands to the exact phase: sets of objects (each possibly restricted to a
// subset of its triangles) such that no two objects of different sets, and no pruned object,
// can collide. A set may also list the only member pairs that can collide in it (Quick-CULLIDE's
// classification), each side of a pair restricted to some of its member's triangles.
#include <cstdint>
#include <optional>
#include <vector>

#include "scenes/SceneGeometry.h"

namespace cdb {

struct SetMember {
  ObjectId object = 0;
  // Local triangle indices that may still collide; empty means every triangle of the mesh.
  std::vector<std::uint32_t> triangles;
  bool allTriangles() const { return triangles.empty(); }
};

// Two members of one set that may collide. Each side's triangles are positions in its member's
// triangle list (SetMember::triangles, or the mesh's triangles when the member keeps all); empty
// means all of the member's triangles.
struct MemberPair {
  std::uint32_t first = 0;   // index into PotentiallyCollidingSet::members
  std::uint32_t second = 0;
  std::vector<std::uint32_t> firstTriangles;
  std::vector<std::uint32_t> secondTriangles;
};

struct PotentiallyCollidingSet {
  std::vector<SetMember> members;
  // Unset: any two members may collide (the exact phase sweeps them all). Set: only these pairs
  // may; every other pair of members is known not to collide.
  std::optional<std::vector<MemberPair>> pairs = std::nullopt;
};

using PotentiallyCollidingSets = std::vector<PotentiallyCollidingSet>;

}  // namespace cdb
