#pragma once
// One call through the VisibilityBackend interface with its arguments, as the recording backend
// keeps them for a replay and the scripted oracle keeps them for a test to inspect.
#include <cstdint>
#include <span>
#include <vector>

#include "culling/visibility/VisibilityBackend.h"

namespace cdb {

struct VisibilityCall {
  enum class Kind {
    SetOptions,
    AttachScene,
    SetPoses,
    BeginPass,
    QueryRange,
    QueryBox,
    WriteRange,
    WriteTriangles,
    WriteBox,
    FetchResults,
    QueryTriangleRange,  // each triangle of `range`
    QueryTriangles,      // each of `triangles` of `object`
    QueryBoxes,          // each of `boxes` of `object`
    WriteBoxes,
    GateAnswers  // answers `gated`.. gated by answers `gate`.., `count` each
  };
  Kind kind = Kind::BeginPass;
  int pass = -1;                         // the pass it belongs to (0, 1, ...), where the log counts them
  VisibilityOptions options;             // SetOptions
  const SceneGeometry* scene = nullptr;  // AttachScene (not owned)
  std::vector<Pose> poses;               // SetPoses
  ViewSpec view;                         // BeginPass
  DepthUse depth = DepthUse::Fresh;      // BeginPass
  MeshRange range;                       // QueryRange, WriteRange, QueryTriangleRange
  ObjectId object = 0;                   // every call on a piece of one object
  OrientedBox box;                       // QueryBox, WriteBox
  std::vector<std::uint32_t> triangles;  // WriteTriangles, QueryTriangles
  std::vector<OrientedBox> boxes;        // QueryBoxes, WriteBoxes
  std::vector<std::uint8_t> answers;     // FetchResults: what the recorded backend answered
  QueryIndex gated = 0, gate = 0;        // GateAnswers
  std::uint32_t count = 0;               // GateAnswers

  [[nodiscard]] static VisibilityCall ofRange(Kind kind, const MeshRange& range) {
    VisibilityCall c;
    c.kind = kind;
    c.object = range.object;
    c.range = range;
    return c;
  }
  [[nodiscard]] static VisibilityCall ofBox(Kind kind, ObjectId object, const OrientedBox& box) {
    VisibilityCall c;
    c.kind = kind;
    c.object = object;
    c.box = box;
    return c;
  }
  [[nodiscard]] static VisibilityCall ofTriangles(Kind kind, ObjectId object,
                                                  std::span<const std::uint32_t> triangles) {
    VisibilityCall c;
    c.kind = kind;
    c.object = object;
    c.triangles.assign(triangles.begin(), triangles.end());
    return c;
  }
  [[nodiscard]] static VisibilityCall ofBoxes(Kind kind, ObjectId object,
                                              std::span<const OrientedBox> boxes) {
    VisibilityCall c;
    c.kind = kind;
    c.object = object;
    c.boxes.assign(boxes.begin(), boxes.end());
    return c;
  }
  [[nodiscard]] static VisibilityCall ofPass(const ViewSpec& view, DepthUse depth) {
    VisibilityCall c;
    c.kind = Kind::BeginPass;
    c.view = view;
    c.depth = depth;
    return c;
  }
};

}  // namespace cdb
