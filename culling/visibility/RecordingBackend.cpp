#include "culling/visibility/RecordingBackend.h"

namespace cdb {

RecordingBackend::RecordingBackend(VisibilityBackend& inner)
    : inner_(inner), name_("recording:" + std::string(inner.name())) {}

RecordedOp& RecordingBackend::log(RecordedOp::Kind kind) {
  RecordedOp& op = ops_.emplace_back();
  op.kind = kind;
  return op;
}

void RecordingBackend::setOptions(const VisibilityOptions& options) {
  inner_.setOptions(options);
  log(RecordedOp::Kind::SetOptions).options = options;
}

void RecordingBackend::attachScene(const SceneGeometry& scene) {
  inner_.attachScene(scene);
  log(RecordedOp::Kind::AttachScene).scene = &scene;
}

void RecordingBackend::setPoses(std::span<const Pose> poses) {
  inner_.setPoses(poses);
  log(RecordedOp::Kind::SetPoses).poses.assign(poses.begin(), poses.end());
}

void RecordingBackend::beginPass(const ViewSpec& view, DepthUse depth) {
  inner_.beginPass(view, depth);
  RecordedOp& op = log(RecordedOp::Kind::BeginPass);
  op.view = view;
  op.depth = depth;
}

QueryIndex RecordingBackend::queryRange(const MeshRange& range) {
  const QueryIndex index = inner_.queryRange(range);
  log(RecordedOp::Kind::QueryRange).range = range;
  return index;
}

QueryIndex RecordingBackend::queryBox(ObjectId object, const OrientedBox& localBox) {
  const QueryIndex index = inner_.queryBox(object, localBox);
  RecordedOp& op = log(RecordedOp::Kind::QueryBox);
  op.object = object;
  op.box = localBox;
  return index;
}

QueryIndex RecordingBackend::queryTriangles(const MeshRange& range) {
  const QueryIndex index = inner_.queryTriangles(range);
  log(RecordedOp::Kind::QueryTriangleRange).range = range;
  return index;
}

QueryIndex RecordingBackend::queryTriangles(ObjectId object,
                                            std::span<const std::uint32_t> triangles) {
  const QueryIndex index = inner_.queryTriangles(object, triangles);
  RecordedOp& op = log(RecordedOp::Kind::QueryTriangles);
  op.object = object;
  op.triangles.assign(triangles.begin(), triangles.end());
  return index;
}

QueryIndex RecordingBackend::queryBoxes(ObjectId object, std::span<const OrientedBox> localBoxes) {
  const QueryIndex index = inner_.queryBoxes(object, localBoxes);
  RecordedOp& op = log(RecordedOp::Kind::QueryBoxes);
  op.object = object;
  op.boxes.assign(localBoxes.begin(), localBoxes.end());
  return index;
}

void RecordingBackend::writeBoxes(ObjectId object, std::span<const OrientedBox> localBoxes) {
  inner_.writeBoxes(object, localBoxes);
  RecordedOp& op = log(RecordedOp::Kind::WriteBoxes);
  op.object = object;
  op.boxes.assign(localBoxes.begin(), localBoxes.end());
}

void RecordingBackend::writeRange(const MeshRange& range) {
  inner_.writeRange(range);
  log(RecordedOp::Kind::WriteRange).range = range;
}

void RecordingBackend::writeTriangles(ObjectId object, std::span<const std::uint32_t> triangles) {
  inner_.writeTriangles(object, triangles);
  RecordedOp& op = log(RecordedOp::Kind::WriteTriangles);
  op.object = object;
  op.triangles.assign(triangles.begin(), triangles.end());
}

void RecordingBackend::writeBox(ObjectId object, const OrientedBox& localBox) {
  inner_.writeBox(object, localBox);
  RecordedOp& op = log(RecordedOp::Kind::WriteBox);
  op.object = object;
  op.box = localBox;
}

void RecordingBackend::fetchResults(std::vector<std::uint8_t>& fullyVisible) {
  inner_.fetchResults(fullyVisible);
  log(RecordedOp::Kind::FetchResults).answers = fullyVisible;
}

void replayOps(VisibilityBackend& target, std::span<const RecordedOp> ops,
               std::vector<std::vector<std::uint8_t>>* answers) {
  std::vector<std::uint8_t> discarded;
  std::size_t fetches = 0;
  if (answers)
    for (const RecordedOp& op : ops) fetches += op.kind == RecordedOp::Kind::FetchResults ? 1 : 0;
  if (answers) answers->resize(fetches);
  std::size_t fetch = 0;
  for (const RecordedOp& op : ops) {
    switch (op.kind) {
      case RecordedOp::Kind::SetOptions:
        target.setOptions(op.options);
        break;
      case RecordedOp::Kind::AttachScene:
        target.attachScene(*op.scene);
        break;
      case RecordedOp::Kind::SetPoses:
        target.setPoses(op.poses);
        break;
      case RecordedOp::Kind::BeginPass:
        target.beginPass(op.view, op.depth);
        break;
      case RecordedOp::Kind::QueryRange:
        target.queryRange(op.range);
        break;
      case RecordedOp::Kind::QueryBox:
        target.queryBox(op.object, op.box);
        break;
      case RecordedOp::Kind::WriteRange:
        target.writeRange(op.range);
        break;
      case RecordedOp::Kind::WriteTriangles:
        target.writeTriangles(op.object, op.triangles);
        break;
      case RecordedOp::Kind::WriteBox:
        target.writeBox(op.object, op.box);
        break;
      case RecordedOp::Kind::FetchResults:
        target.fetchResults(answers ? (*answers)[fetch++] : discarded);
        break;
      case RecordedOp::Kind::QueryTriangleRange:
        target.queryTriangles(op.range);
        break;
      case RecordedOp::Kind::QueryTriangles:
        target.queryTriangles(op.object, op.triangles);
        break;
      case RecordedOp::Kind::QueryBoxes:
        target.queryBoxes(op.object, op.boxes);
        break;
      case RecordedOp::Kind::WriteBoxes:
        target.writeBoxes(op.object, op.boxes);
        break;
    }
  }
}

}  // namespace cdb
