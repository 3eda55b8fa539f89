#pragma once
// Draws a scene at one frame's poses as a picture: every object shaded in its own colour (a light
// from above the camera, a depth cue that darkens what is far), line segments as thin bars (the
// container's edges), through the headless GL context into an off-screen framebuffer. Beside the
// colours it reads back which object covers each pixel, for outlines and tests.
#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "core/Pose.h"
#include "render/Camera.h"
#include "render/GlHandle.h"
#include "render/Image.h"
#include "scenes/SceneGeometry.h"

namespace cdb {

class HeadlessGlContext;

struct Segment {
  Eigen::Vector3d from = Eigen::Vector3d::Zero();
  Eigen::Vector3d to = Eigen::Vector3d::Zero();
};

struct SceneDrawing {
  std::span<const Pose> poses;   // one per object of the attached scene
  std::span<const Rgb> colours;  // one per object
  std::span<const Segment> segments;
  double segmentWidth = 0.0;         // world units
  Rgb segmentColour{105, 115, 135};  // slate: apart from the grey of pruned objects
};

struct RenderedScene {
  static constexpr std::uint32_t kNothing = 0;            // background
  static constexpr std::uint32_t kSegment = 0xffffffffu;  // a segment's bar
  RgbImage colour;  // background pixels are black: the caller paints its own background
  std::vector<std::uint32_t> ids;  // per pixel, rows from the top: object + 1, kSegment or kNothing
};

class SceneRenderer {
 public:
  // Compiles the program in `context` and makes it current; `context` must outlive the renderer.
  explicit SceneRenderer(HeadlessGlContext& context);
  // Makes the context current again so that the GL objects are deleted where they live.
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  // Uploads every mesh of `scene` with smooth vertex normals (the previous scene's are released).
  void attach(const SceneGeometry& scene);
  // The largest width or height render() takes.
  [[nodiscard]] int maxSize() const { return maxSize_; }
  // Throws RunError for a size outside 1..maxSize() or a drawing that does not match the scene.
  [[nodiscard]] RenderedScene render(const Camera& camera, const SceneDrawing& drawing, int width,
                                     int height);

 private:
  struct MeshSlot {
    std::uint32_t firstIndex = 0, indexCount = 0;
    std::int32_t baseVertex = 0;
  };
  void ensureTarget(int width, int height);

  HeadlessGlContext* context_;
  GlProgramName program_;
  GlVertexArray vao_;
  GlBuffer vertices_, indices_;
  std::vector<MeshSlot> meshes_;  // the scene's meshes, then the bar
  std::vector<std::uint32_t> objectMesh_;
  GlFramebuffer framebuffer_;
  GlRenderbuffer colour_, ids_, depth_;
  int targetWidth_ = 0, targetHeight_ = 0;
  int maxSize_ = 0;
};

}  // namespace cdb
