#pragma once
// A scripted oracle that decides "fully visible" from the geometry instead of a script of answers:
// each queried or written piece stands for the world AABB of its triangles, decided as
// AxisViewOcclusion.h says. Exact for boxes, and conservative for any content of the boxes: pieces
// that touch are never fully visible with respect to each other.
#include <gtest/gtest.h>

#include <span>
#include <vector>

#include "AxisViewOcclusion.h"
#include "culling/visibility/ScriptedVisibilityOracle.h"

namespace cdb::testing {

class GeometricOracle {
 public:
  struct Answer {
    int pass = 0;
    ObjectId object = 0;
    bool wholeObject = false;
    bool fullyVisible = false;
  };

  explicit GeometricOracle(const SceneGeometry& scene)
      : scene_(scene), oracle_([this](const VisibilityCall& q, std::span<const VisibilityCall> written) {
          return decide(q, written);
        }) {}
  GeometricOracle(const GeometricOracle&) = delete;
  GeometricOracle& operator=(const GeometricOracle&) = delete;

  ScriptedVisibilityOracle& backend() { return oracle_; }
  const std::vector<Answer>& answers() const { return answers_; }

  // Objects with a whole-object query in `pass` that was not fully visible.
  std::vector<ObjectId> hiddenObjects(int pass) const {
    std::vector<ObjectId> out;
    for (const auto& a : answers_)
      if (a.pass == pass && a.wholeObject && !a.fullyVisible) out.push_back(a.object);
    return out;
  }

  // World box of a piece of an object's mesh under the current poses.
  Aabb pieceBox(ObjectId object, std::span<const std::uint32_t> triangles) const {
    const Mesh& mesh = scene_.meshOf(object);
    const Pose& pose = oracle_.poses()[object];
    Aabb box;
    for (std::uint32_t t : triangles)
      for (std::uint32_t v : mesh.triangles[t]) box.extend(pose.apply(mesh.vertices[v].cast<double>()));
    return box;
  }

 private:
  Aabb boxOf(const VisibilityCall& c) const {
    std::vector<std::uint32_t> tris;
    if (c.kind == VisibilityCall::Kind::WriteTriangles) {
      tris = c.triangles;
    } else {
      EXPECT_TRUE(c.kind == VisibilityCall::Kind::QueryRange || c.kind == VisibilityCall::Kind::WriteRange)
          << "the geometric oracle decides mesh pieces only";
      for (std::uint32_t t = 0; t < c.range.triangleCount; ++t)
        tris.push_back(c.range.firstTriangle + t);
    }
    return pieceBox(c.object, tris);
  }

  bool decide(const VisibilityCall& q, std::span<const VisibilityCall> written) {
    const bool visible = fullyVisibleAlongAxis(oracle_, boxOf(q), written,
                                               [this](const VisibilityCall& w) { return boxOf(w); });
    const bool whole = q.range.firstTriangle == 0 &&
                       q.range.triangleCount == scene_.meshOf(q.object).triangleCount();
    answers_.push_back({q.pass, q.object, whole, visible});
    return visible;
  }

  const SceneGeometry& scene_;
  ScriptedVisibilityOracle oracle_;
  std::vector<Answer> answers_;
};

}  // namespace cdb::testing
