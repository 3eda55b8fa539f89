#pragma once
// Visibility draws of an object's active nodes as one group: every node is queried before any
// is written, so nodes of one object never count as occluding each other.
#include "culling/bvh/NodeFrontier.h"
#include "culling/visibility/VisibilityBackend.h"

namespace cdb {

// Queries every active node of `object`; returns the first query's index (the others follow
// it, in the frontier's order).
inline QueryIndex queryNodes(VisibilityBackend& backend, const NodeFrontier& frontier,
                             ObjectId object) {
  const auto nodes = frontier.nodes(object);
  QueryIndex first = 0;
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const QueryIndex q = backend.queryBox(object, frontier.box(object, nodes[k]));
    if (k == 0) first = q;
  }
  return first;
}

inline void writeNodes(VisibilityBackend& backend, const NodeFrontier& frontier, ObjectId object) {
  for (std::uint32_t node : frontier.nodes(object))
    backend.writeBox(object, frontier.box(object, node));
}

}  // namespace cdb
