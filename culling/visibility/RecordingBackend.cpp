#include "culling/visibility/RecordingBackend.h"

namespace cdb {

RecordingBackend::RecordingBackend(VisibilityBackend& inner)
    : inner_(inner), name_("recording:" + std::string(inner.name())) {}

VisibilityCall& RecordingBackend::log(VisibilityCall::Kind kind) {
  VisibilityCall& op = ops_.emplace_back();
  op.kind = kind;
  return op;
}

void RecordingBackend::setOptions(const VisibilityOptions& options) {
  inner_.setOptions(options);
  log(VisibilityCall::Kind::SetOptions).options = options;
}

void RecordingBackend::attachScene(const SceneGeometry& scene) {
  inner_.attachScene(scene);
  log(VisibilityCall::Kind::AttachScene).scene = &scene;
}

void RecordingBackend::setPoses(std::span<const Pose> poses) {
  inner_.setPoses(poses);
  log(VisibilityCall::Kind::SetPoses).poses.assign(poses.begin(), poses.end());
}

void RecordingBackend::beginPass(const ViewSpec& view, DepthUse depth) {
  inner_.beginPass(view, depth);
  log(VisibilityCall::ofPass(view, depth));
}

QueryIndex RecordingBackend::queryRange(const MeshRange& range) {
  const QueryIndex index = inner_.queryRange(range);
  log(VisibilityCall::ofRange(VisibilityCall::Kind::QueryRange, range));
  return index;
}

QueryIndex RecordingBackend::queryBox(ObjectId object, const OrientedBox& localBox) {
  const QueryIndex index = inner_.queryBox(object, localBox);
  log(VisibilityCall::ofBox(VisibilityCall::Kind::QueryBox, object, localBox));
  return index;
}

QueryIndex RecordingBackend::queryTriangles(const MeshRange& range) {
  const QueryIndex index = inner_.queryTriangles(range);
  log(VisibilityCall::ofRange(VisibilityCall::Kind::QueryTriangleRange, range));
  return index;
}

QueryIndex RecordingBackend::queryTriangles(ObjectId object,
                                            std::span<const std::uint32_t> triangles) {
  const QueryIndex index = inner_.queryTriangles(object, triangles);
  log(VisibilityCall::ofTriangles(VisibilityCall::Kind::QueryTriangles, object, triangles));
  return index;
}

QueryIndex RecordingBackend::queryBoxes(ObjectId object, std::span<const OrientedBox> localBoxes) {
  const QueryIndex index = inner_.queryBoxes(object, localBoxes);
  log(VisibilityCall::ofBoxes(VisibilityCall::Kind::QueryBoxes, object, localBoxes));
  return index;
}

void RecordingBackend::writeBoxes(ObjectId object, std::span<const OrientedBox> localBoxes) {
  inner_.writeBoxes(object, localBoxes);
  log(VisibilityCall::ofBoxes(VisibilityCall::Kind::WriteBoxes, object, localBoxes));
}

void RecordingBackend::writeRange(const MeshRange& range) {
  inner_.writeRange(range);
  log(VisibilityCall::ofRange(VisibilityCall::Kind::WriteRange, range));
}

void RecordingBackend::writeTriangles(ObjectId object, std::span<const std::uint32_t> triangles) {
  inner_.writeTriangles(object, triangles);
  log(VisibilityCall::ofTriangles(VisibilityCall::Kind::WriteTriangles, object, triangles));
}

void RecordingBackend::writeBox(ObjectId object, const OrientedBox& localBox) {
  inner_.writeBox(object, localBox);
  log(VisibilityCall::ofBox(VisibilityCall::Kind::WriteBox, object, localBox));
}

void RecordingBackend::fetchAnswers(std::vector<std::uint8_t>& fullyVisible) {
  inner_.fetchResults(fullyVisible);
  log(VisibilityCall::Kind::FetchResults).answers = fullyVisible;
}

void RecordingBackend::gateSet(QueryIndex gated, QueryIndex gate, std::uint32_t count) {
  inner_.gateAnswers(gated, gate, count);
  VisibilityCall& op = log(VisibilityCall::Kind::GateAnswers);
  op.gated = gated, op.gate = gate, op.count = count;
}

void replayOps(VisibilityBackend& target, std::span<const VisibilityCall> ops,
               std::vector<std::vector<std::uint8_t>>* answers, bool attachScenes) {
  std::vector<std::uint8_t> discarded;
  std::size_t fetches = 0;
  if (answers)
    for (const VisibilityCall& op : ops)
      fetches += op.kind == VisibilityCall::Kind::FetchResults ? 1 : 0;
  if (answers) answers->resize(fetches);
  std::size_t fetch = 0;
  for (const VisibilityCall& op : ops) {
    switch (op.kind) {
      case VisibilityCall::Kind::SetOptions:
        target.setOptions(op.options);
        break;
      case VisibilityCall::Kind::AttachScene:
        if (attachScenes) target.attachScene(*op.scene);
        break;
      case VisibilityCall::Kind::SetPoses:
        target.setPoses(op.poses);
        break;
      case VisibilityCall::Kind::BeginPass:
        target.beginPass(op.view, op.depth);
        break;
      case VisibilityCall::Kind::QueryRange:
        target.queryRange(op.range);
        break;
      case VisibilityCall::Kind::QueryBox:
        target.queryBox(op.object, op.box);
        break;
      case VisibilityCall::Kind::WriteRange:
        target.writeRange(op.range);
        break;
      case VisibilityCall::Kind::WriteTriangles:
        target.writeTriangles(op.object, op.triangles);
        break;
      case VisibilityCall::Kind::WriteBox:
        target.writeBox(op.object, op.box);
        break;
      case VisibilityCall::Kind::FetchResults:
        target.fetchResults(answers ? (*answers)[fetch++] : discarded);
        break;
      case VisibilityCall::Kind::QueryTriangleRange:
        target.queryTriangles(op.range);
        break;
      case VisibilityCall::Kind::QueryTriangles:
        target.queryTriangles(op.object, op.triangles);
        break;
      case VisibilityCall::Kind::QueryBoxes:
        target.queryBoxes(op.object, op.boxes);
        break;
      case VisibilityCall::Kind::WriteBoxes:
        target.writeBoxes(op.object, op.boxes);
        break;
      case VisibilityCall::Kind::GateAnswers:
        target.gateAnswers(op.gated, op.gate, op.count);
        break;
    }
  }
}

}  // namespace cdb
