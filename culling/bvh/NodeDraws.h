#pragma once
// Visibility draws of an object's active nodes as one group: every node is queried before any
// is written (one batch each), so nodes of one object never count as occluding each other.
#include <vector>

#include "culling/bvh/NodeFrontier.h"
#include "culling/visibility/VisibilityBackend.h"

namespace cdb {

// The boxes of `object`'s active nodes, in the frontier's order, into `boxes`.
inline void gatherNodeBoxes(const NodeFrontier& frontier, ObjectId object,
                            std::vector<OrientedBox>& boxes) {
  boxes.clear();
  for (std::uint32_t node : frontier.nodes(object)) boxes.push_back(frontier.box(object, node));
}

// Queries every active node of `object` in one batch; returns the first query's index (the
// others follow it, in the frontier's order). `boxes` is scratch space.
inline QueryIndex queryNodes(VisibilityBackend& backend, const NodeFrontier& frontier,
                             ObjectId object, std::vector<OrientedBox>& boxes) {
  gatherNodeBoxes(frontier, object, boxes);
  return backend.queryBoxes(object, boxes);
}

inline void writeNodes(VisibilityBackend& backend, const NodeFrontier& frontier, ObjectId object,
                       std::vector<OrientedBox>& boxes) {
  gatherNodeBoxes(frontier, object, boxes);
  backend.writeBoxes(object, boxes);
}

}  // namespace cdb
