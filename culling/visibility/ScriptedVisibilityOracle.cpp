#include "culling/visibility/ScriptedVisibilityOracle.h"

#include "core/Errors.h"

namespace cdb {

void ScriptedVisibilityOracle::beginPass(const ViewSpec& view, DepthUse depth) {
  ++pass_;
  depth_ = depth;
  tested_ = false;
  VisibilityCall call = VisibilityCall::ofPass(view, depth);
  call.pass = pass_;
  log_.push_back(std::move(call));
  if (depth != DepthUse::SharedSecond) {
    passWrites_.clear();
    ++counters_.depthClears;
  } else {
    passWrites_.clear();  // the shared second pass sees nothing of the first one
  }
  ++counters_.passes;
}

QueryIndex ScriptedVisibilityOracle::query(VisibilityCall call) {
  call.pass = pass_;
  tested_ = true;
  bool visible;
  if (depth_ == DepthUse::OrderIndependent) {
    std::vector<VisibilityCall> others;
    for (const VisibilityCall& w : passWrites_)
      if (w.object != call.object) others.push_back(w);
    visible = script_(call, others);
  } else {
    visible = script_(call, passWrites_);
  }
  log_.push_back(std::move(call));
  pending_.push_back(visible ? 1 : 0);
  ++counters_.queries;
  ++counters_.draws;
  return static_cast<QueryIndex>(pending_.size() - 1);
}

void ScriptedVisibilityOracle::write(VisibilityCall call) {
  if (depth_ == DepthUse::OrderIndependent && tested_)
    throw RunError("a write after a test in an order-independent pass");
  call.pass = pass_;
  log_.push_back(call);
  passWrites_.push_back(std::move(call));
  ++counters_.draws;
}

QueryIndex ScriptedVisibilityOracle::queryRange(const MeshRange& range) {
  counters_.trianglesDrawn += range.triangleCount;
  return query(VisibilityCall::ofRange(VisibilityCall::Kind::QueryRange, range));
}

QueryIndex ScriptedVisibilityOracle::queryBox(ObjectId object, const OrientedBox& localBox) {
  counters_.trianglesDrawn += 12;
  return query(VisibilityCall::ofBox(VisibilityCall::Kind::QueryBox, object, localBox));
}

void ScriptedVisibilityOracle::writeRange(const MeshRange& range) {
  counters_.trianglesDrawn += range.triangleCount;
  write(VisibilityCall::ofRange(VisibilityCall::Kind::WriteRange, range));
}

void ScriptedVisibilityOracle::writeTriangles(ObjectId object,
                                              std::span<const std::uint32_t> triangles) {
  counters_.trianglesDrawn += triangles.size();
  write(VisibilityCall::ofTriangles(VisibilityCall::Kind::WriteTriangles, object, triangles));
}

void ScriptedVisibilityOracle::writeBox(ObjectId object, const OrientedBox& localBox) {
  counters_.trianglesDrawn += 12;
  write(VisibilityCall::ofBox(VisibilityCall::Kind::WriteBox, object, localBox));
}

void ScriptedVisibilityOracle::fetchAnswers(std::vector<std::uint8_t>& fullyVisible) {
  fullyVisible = std::move(pending_);
  pending_.clear();
  ++counters_.fetches;
}

std::vector<ObjectId> ScriptedVisibilityOracle::queriedObjects(int pass) const {
  std::vector<ObjectId> out;
  for (const auto& c : log_) {
    if (c.pass == pass && (c.kind == VisibilityCall::Kind::QueryRange || c.kind == VisibilityCall::Kind::QueryBox))
      out.push_back(c.object);
  }
  return out;
}

}  // namespace cdb
