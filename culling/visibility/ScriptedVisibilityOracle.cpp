#include "culling/visibility/ScriptedVisibilityOracle.h"

namespace cdb {

void ScriptedVisibilityOracle::beginPass(const ViewSpec& view, DepthUse depth) {
  ++pass_;
  OracleCall call;
  call.kind = OracleCall::Kind::BeginPass;
  call.pass = pass_;
  call.view = view;
  call.depth = depth;
  log_.push_back(call);
  if (depth != DepthUse::SharedSecond) {
    passWrites_.clear();
    ++counters_.depthClears;
  } else {
    passWrites_.clear();  // the shared second pass sees nothing of the first one
  }
  ++counters_.passes;
}

QueryIndex ScriptedVisibilityOracle::query(OracleCall call) {
  call.pass = pass_;
  const bool visible = script_(call, passWrites_);
  log_.push_back(std::move(call));
  pending_.push_back(visible ? 1 : 0);
  ++counters_.queries;
  ++counters_.draws;
  return static_cast<QueryIndex>(pending_.size() - 1);
}

void ScriptedVisibilityOracle::write(OracleCall call) {
  call.pass = pass_;
  log_.push_back(call);
  passWrites_.push_back(std::move(call));
  ++counters_.draws;
}

QueryIndex ScriptedVisibilityOracle::queryRange(const MeshRange& range) {
  OracleCall call;
  call.kind = OracleCall::Kind::QueryRange;
  call.object = range.object;
  call.range = range;
  counters_.trianglesDrawn += range.triangleCount;
  return query(std::move(call));
}

QueryIndex ScriptedVisibilityOracle::queryBox(ObjectId object, const OrientedBox& localBox) {
  OracleCall call;
  call.kind = OracleCall::Kind::QueryBox;
  call.object = object;
  call.box = localBox;
  counters_.trianglesDrawn += 12;
  return query(std::move(call));
}

void ScriptedVisibilityOracle::writeRange(const MeshRange& range) {
  OracleCall call;
  call.kind = OracleCall::Kind::WriteRange;
  call.object = range.object;
  call.range = range;
  counters_.trianglesDrawn += range.triangleCount;
  write(std::move(call));
}

void ScriptedVisibilityOracle::writeTriangles(ObjectId object,
                                              std::span<const std::uint32_t> triangles) {
  OracleCall call;
  call.kind = OracleCall::Kind::WriteTriangles;
  call.object = object;
  call.triangles.assign(triangles.begin(), triangles.end());
  counters_.trianglesDrawn += triangles.size();
  write(std::move(call));
}

void ScriptedVisibilityOracle::writeBox(ObjectId object, const OrientedBox& localBox) {
  OracleCall call;
  call.kind = OracleCall::Kind::WriteBox;
  call.object = object;
  call.box = localBox;
  counters_.trianglesDrawn += 12;
  write(std::move(call));
}

void ScriptedVisibilityOracle::fetchResults(std::vector<std::uint8_t>& fullyVisible) {
  fullyVisible = std::move(pending_);
  pending_.clear();
  ++counters_.fetches;
}

std::vector<ObjectId> ScriptedVisibilityOracle::queriedObjects(int pass) const {
  std::vector<ObjectId> out;
  for (const auto& c : log_) {
    if (c.pass == pass && (c.kind == OracleCall::Kind::QueryRange || c.kind == OracleCall::Kind::QueryBox))
      out.push_back(c.object);
  }
  return out;
}

}  // namespace cdb
