#pragma once
// The visibility backend on flags in a storage buffer: the occlusion-query backend's pipeline,
// rasterisation and conservative rules, but a batch of tests (every triangle of a range or a list,
// every box of a list) is one draw, and a test answers through its piece's flag, which any
// fragment of the piece at or behind the stored depth sets (FlagShaders.h). One read-back per
// fetch answers every test since the last; no query objects, whose per-query cost dominates on
// llvmpipe.
#include <cstdint>
#include <vector>

#include "culling/visibility/GlItemFlags.h"
#include "culling/visibility/GlStreamBuffer.h"
#include "culling/visibility/GlVisibilityPipeline.h"
#include "culling/visibility/VisibilityBackend.h"

namespace cdb {

class GlFlagBackend final : public VisibilityBackend {
 public:
  // The backend's GL objects live in `context`, which must outlive it.
  explicit GlFlagBackend(HeadlessGlContext& context, const VisibilityOptions& options = {});
  // Makes the context current so that the buffers are deleted where they live.
  ~GlFlagBackend() override;
  GlFlagBackend(const GlFlagBackend&) = delete;
  GlFlagBackend& operator=(const GlFlagBackend&) = delete;

  [[nodiscard]] std::string_view name() const override { return "gl-flags"; }
  [[nodiscard]] std::string renderer() const override;
  [[nodiscard]] int maxResolution() const override { return pipeline_.maxResolution(); }
  void setOptions(const VisibilityOptions& options) override;

  void attachScene(const SceneGeometry& scene) override;
  void setPoses(std::span<const Pose> poses) override;
  // SharedSecond must follow a SharedFirst pass at the same resolution; RunError otherwise.
  void beginPass(const ViewSpec& view, DepthUse depth) override;

  QueryIndex queryRange(const MeshRange& range) override;
  QueryIndex queryBox(ObjectId object, const OrientedBox& localBox) override;
  QueryIndex queryTriangles(const MeshRange& range) override;
  QueryIndex queryTriangles(ObjectId object, std::span<const std::uint32_t> triangles) override;
  QueryIndex queryBoxes(ObjectId object, std::span<const OrientedBox> localBoxes) override;

  void writeRange(const MeshRange& range) override;
  void writeTriangles(ObjectId object, std::span<const std::uint32_t> triangles) override;
  void writeBox(ObjectId object, const OrientedBox& localBox) override;
  void writeBoxes(ObjectId object, std::span<const OrientedBox> localBoxes) override;

  void fetchResults(std::vector<std::uint8_t>& fullyVisible) override;

  [[nodiscard]] VisibilityCounters counters() const override { return counters_; }
  void resetCounters() override { counters_ = {}; }

 private:
  // Draws of checked arguments; `item` is the first item of a test (ignored by writes).
  void drawRange(const MeshRange& range, DrawRole role, std::uint32_t item, bool itemPerTriangle);
  // `triangles` already gathered by gatherList, which said whether they are `consecutive`.
  void drawList(ObjectId object, std::span<const std::uint32_t> triangles, bool consecutive,
                DrawRole role, std::uint32_t item);
  void drawBoxes(ObjectId object, std::span<const OrientedBox> boxes, DrawRole role,
                 std::uint32_t item);
  void drawBox(ObjectId object, const OrientedBox& box, DrawRole role, std::uint32_t item);
  // `triangles` of `object` as global triangle indices into listScratch_ (RunError for one
  // outside the mesh); returns whether they are consecutive.
  bool gatherList(ObjectId object, std::span<const std::uint32_t> triangles);
  void countDraw(std::uint64_t triangles) {
    ++counters_.draws;
    counters_.trianglesDrawn += triangles;
  }

  HeadlessGlContext* context_;
  GlVisibilityPipeline pipeline_;
  GlItemFlags flags_;
  GlStreamBuffer listedTriangles_, boxMatrices_;
  VisibilityCounters counters_;
  // Scratch reused so that a frame allocates nothing.
  std::vector<std::uint32_t> listScratch_;
  std::vector<float> boxScratch_;
};

}  // namespace cdb
