#pragma once
// The boxes drawn for an object's active nodes: every node is queried before any is written (one
// batch each), so nodes of one object never count as occluding each other.
#include <vector>

#include "culling/bvh/NodeFrontier.h"

namespace cdb {

// The boxes of `object`'s active nodes, in the frontier's order, appended to `boxes` (a
// std::vector<OrientedBox> or a GrowOnlyArray of them).
template <class Boxes>
void appendNodeBoxes(const NodeFrontier& frontier, ObjectId object, Boxes& boxes) {
  for (std::uint32_t node : frontier.nodes(object)) boxes.push_back(frontier.box(object, node));
}

}  // namespace cdb
