#pragma once
// The visibility backend on flags in a storage buffer: the occlusion-query backend's pipeline,
// rasterisation and conservative rules, but a batch of tests (every triangle of a range or a list,
// every box of a list) is one draw, and a test answers through its piece's flag, which any
// fragment of the piece at or behind the stored depth sets (FlagShaders.h). One read-back per
// fetch answers every test since the last; no query objects, whose per-query cost dominates on
// llvmpipe.
//
// Order-independent passes (DepthUse::OrderIndependent, FlagShaders.h): the pass' writes and
// tests are gathered as segments of pieces, not drawn one call at a time. The writes are drawn at
// the pass' first test (or fetch) in two draws, the nearest depth with its object and the others'
// nearest depth; the tests at the fetch (or the next pass) in one draw that compares each fragment
// with them. So a pass is three draws however many pieces it has, with the same rasterisation and
// conservative depths as the other passes: a piece is answered as CULLIDE's two Fresh passes
// answer it together.
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
  [[nodiscard]] bool supportsOrderIndependent() const override { return true; }
  void setOptions(const VisibilityOptions& options) override;

  void attachScene(const SceneGeometry& scene) override;
  void setPoses(std::span<const Pose> poses) override;
  // SharedSecond must follow a SharedFirst pass at the same resolution; RunError otherwise. A write
  // after a test in an OrderIndependent pass is a RunError.
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


  [[nodiscard]] VisibilityCounters counters() const override { return counters_; }
  void resetCounters() override { counters_ = {}; }

 protected:
  void fetchAnswers(std::vector<std::uint8_t>& fullyVisible) override;

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

  // The pieces of an order-independent pass gathered for one batch of draws.
  struct PassBatch {
    std::vector<std::uint32_t> segments;       // four per segment (FlagShaders.h)
    std::vector<std::uint8_t> triangles;       // per segment
    std::vector<std::uint32_t> listed;         // global triangle indices of listed segments
    std::vector<float> boxes;                  // box matrices
    std::uint64_t triangleCount = 0;
    [[nodiscard]] std::size_t segmentCount() const { return triangles.size(); }
    void clear();
  };
  // Checked pieces into a batch: `count` triangles of `object` from global triangle `first`, the
  // triangles gathered in listScratch_ (from list entry `listedFirst`), or a box; items from
  // `item` (per triangle or one for all).
  void addRun(PassBatch& batch, ObjectId object, std::uint32_t first, std::uint32_t count,
              std::uint32_t item, bool itemPerTriangle);
  void addListed(PassBatch& batch, ObjectId object, std::uint32_t item);
  void addBox(PassBatch& batch, ObjectId object, const OrientedBox& box, std::uint32_t item);
  // Gathered pieces of an order-independent pass: writes (RunError after a test of the pass) and
  // tests (the first draws the writes).
  PassBatch& passWrites();
  PassBatch& passTests();
  // `batch` into the stream buffers, and where it went; then drawn for a stage (one draw).
  GlVisibilityPipeline::PassBases uploadPassBatch(const PassBatch& batch);
  void drawPassBatch(const PassBatch& batch, PassStage stage,
                     const GlVisibilityPipeline::PassBases& bases);
  // The pass' writes not drawn yet (all of them again, on cleared buffers, when some were).
  void drawPassWrites();
  // The pass' gathered tests, after its writes.
  void drawPassTests();
  HeadlessGlContext* context_;
  GlVisibilityPipeline pipeline_;
  GlItemFlags flags_;
  GlStreamBuffer listedTriangles_, boxMatrices_, passSegments_;
  VisibilityCounters counters_;
  // The current pass is order-independent; it has tested; its writes and tests not drawn yet.
  bool orderIndependent_ = false;
  bool testedInPass_ = false;
  PassBatch passWrites_, passTests_;
  std::size_t writesDrawn_ = 0;  // segments of passWrites_ in the pass' buffers
  // Scratch reused so that a frame allocates nothing.
  std::vector<std::uint32_t> listScratch_;
  std::vector<float> boxScratch_;
};

}  // namespace cdb
