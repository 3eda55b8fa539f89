#pragma once
// The visibility backend on OpenGL occlusion queries, as CULLIDE uses them (Govindaraju et al.
// 2003): a piece is fully visible when its query, drawn with depth writes off and the depth test
// passing at or behind what is stored, counts no sample. Conservative mode (the default) widens
// every triangle to every pixel it touches and draws conservative depths, so no real contact is
// lost at any resolution; raw mode is plain rasterisation with the thesis' small offset.
#include <cstdint>
#include <vector>

#include "culling/visibility/GlVisibilityPipeline.h"
#include "culling/visibility/VisibilityBackend.h"

namespace cdb {

class GlOcclusionQueryBackend final : public VisibilityBackend {
 public:
  // The backend's GL objects live in `context`, which must outlive it.
  explicit GlOcclusionQueryBackend(HeadlessGlContext& context,
                                   const VisibilityOptions& options = {});

  [[nodiscard]] std::string_view name() const override { return "gl-queries"; }
  [[nodiscard]] std::string renderer() const override;
  void setOptions(const VisibilityOptions& options) override;

  void attachScene(const SceneGeometry& scene) override;
  void setPoses(std::span<const Pose> poses) override;

  // SharedSecond must follow a SharedFirst pass at the same resolution (it relies on that pass'
  // clear); otherwise this throws RunError.
  void beginPass(const ViewSpec& view, DepthUse depth) override;

  QueryIndex queryRange(const MeshRange& range) override;
  QueryIndex queryBox(ObjectId object, const OrientedBox& localBox) override;
  void writeRange(const MeshRange& range) override;
  void writeTriangles(ObjectId object, std::span<const std::uint32_t> triangles) override;
  void writeBox(ObjectId object, const OrientedBox& localBox) override;

  [[nodiscard]] VisibilityCounters counters() const override { return counters_; }
  void resetCounters() override { counters_ = {}; }

  // The largest frame-buffer side this GL renders at (GL_MAX_RENDERBUFFER_SIZE and
  // GL_MAX_VIEWPORT_DIMS), so a run can refuse a resolution before it simulates anything.
  [[nodiscard]] int maxResolution() const override { return pipeline_.maxResolution(); }

 protected:
  void fetchAnswers(std::vector<std::uint8_t>& fullyVisible) override;

 private:
  // Draws of already checked arguments.
  void drawRange(const MeshRange& range, DrawRole role);
  void drawBox(ObjectId object, const OrientedBox& box, DrawRole role);

  HeadlessGlContext* context_;
  GlVisibilityPipeline pipeline_;
  VisibilityCounters counters_;
  // Scratch for writeTriangles, reused so that a frame allocates nothing.
  std::vector<GlVisibilityPipeline::Run> runs_;
};

}  // namespace cdb
