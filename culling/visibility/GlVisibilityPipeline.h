#pragma once
// The GL side of visibility tests: the depth-only framebuffer, the programs, the resident scene
// and the query pool, with the state a draw needs cached so that a stream of tests and writes makes
// no redundant GL calls. GlOcclusionQueryBackend and GlFlagBackend put the VisibilityBackend
// contract on top of it; GlDrawFloor replays recorded work on it with nothing else around.
//
// One pipeline draws at a time on a context: beginPass re-establishes every piece of GL state it
// relies on, and within a pass nothing else may draw on the context.
#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "culling/visibility/DepthPassSetup.h"
#include "culling/visibility/PassSequence.h"
#include "culling/visibility/FlagShaders.h"
#include "culling/visibility/GlPassTarget.h"
#include "culling/visibility/GlDrawTimer.h"
#include "culling/visibility/GlQueryPool.h"
#include "culling/visibility/GlSceneBuffers.h"
#include "culling/visibility/OcclusionShaders.h"
#include "render/GlHandle.h"

namespace cdb {

class HeadlessGlContext;

enum class DrawRole : std::uint8_t { None, Test, Write };

// The programs a pipeline draws with.
//  Queries: one program per mode for tests and writes (an occlusion query counts a test's samples).
//  Flags:   a test program and a write program per mode (FlagShaders): a test sets its item's
//           flag; triangles are pulled from the storage buffers in both modes, and a draw may be a
//           batch (a triangle list, instanced boxes). Also the three programs per mode of
//           order-independent passes (FlagShaders.h, drawPass).
enum class PipelinePrograms : std::uint8_t { Queries, Flags };

// The batch uniforms of a Flags pipeline's draw (FlagShaders.h says what they mean).
struct FlagDraw {
  std::int32_t itemBase = 0;
  bool itemPerTriangle = false;
  bool listed = false;
  std::int32_t boxBase = -1;  // < 0: the local matrix of setLocal / setLocalIdentity
  bool operator==(const FlagDraw&) const = default;
};

class GlVisibilityPipeline {
 public:
  // Compiles the programs in `context` and makes it current; `context` must outlive the pipeline.
  explicit GlVisibilityPipeline(HeadlessGlContext& context,
                                PipelinePrograms programs = PipelinePrograms::Queries);
  // Makes the context current again so that the GL objects are deleted where they live.
  ~GlVisibilityPipeline();
  GlVisibilityPipeline(const GlVisibilityPipeline&) = delete;
  GlVisibilityPipeline& operator=(const GlVisibilityPipeline&) = delete;

  void setConservative(bool conservative);
  void setRawDepthOffset(double ndcOffset);
  [[nodiscard]] bool conservative() const { return conservative_; }

  void attach(const SceneGeometry& scene) {
    buffers_.attach(scene);
    sequence_.newScene();
  }
  void uploadPoses(std::span<const Pose> poses) { buffers_.uploadPoses(poses); }
  [[nodiscard]] const GlSceneBuffers& buffers() const { return buffers_; }

  // Binds the framebuffer (re-created when the resolution changes), viewport, depth range and
  // programs for `setup`, and clears when it says so. Throws InputError on a resolution the GL
  // cannot render at. `orderIndependent` (Flags programs only): the pass draws with drawPass into
  // the pass' own buffers (GlPassTarget), which the clear clears.
  void beginPass(const DepthPassSetup& setup, bool orderIndependent = false);
  [[nodiscard]] bool inPass() const { return inPass_; }
  [[nodiscard]] int maxResolution() const { return maxResolution_; }

  // Checked arguments of a visibility call: throws RunError for an object outside the attached
  // scene, triangles outside its mesh, or a draw outside a pass.
  const GlMeshSlot& checkedSlot(ObjectId object) const;
  void checkRange(const MeshRange& range) const;
  // makeDepthPassSetup and beginPass, after checking that a SharedSecond pass follows a
  // SharedFirst pass of the same resolution (it relies on that pass' clear; RunError otherwise).
  // An OrderIndependent pass needs the Flags programs (InputError otherwise).
  DepthPassSetup beginCheckedPass(const ViewSpec& view, DepthUse depth);

  void setRole(DrawRole role) {
    if (role != role_) applyRole(role);
  }
  void setObject(ObjectId object) {
    if (object != object_) {
      glUniform1i(occlusion_uniform::kObject, static_cast<GLint>(object));
      object_ = object;
    }
  }
  void setLocalIdentity() {
    if (!localIdentity_) applyLocal(Eigen::Matrix4f::Identity(), true);
  }
  void setLocal(const Eigen::Matrix4f& local) { applyLocal(local, false); }
  // Flags programs only.
  void setFlagDraw(const FlagDraw& draw) {
    if (!flagDrawSet_ || !(draw == flagDraw_)) applyFlagDraw(draw);
  }

  // Triangles [first, first + count) of a mesh.
  void draw(const GlMeshSlot& slot, std::uint32_t first, std::uint32_t count) {
    const std::uint32_t global = slot.firstTriangle + first;
    if (programs_ == PipelinePrograms::Flags) {
      drawNumbered(global, count);
      return;
    }
    const auto timed = drawTimer_.scope();
    if (pulled())
      glDrawArrays(GL_TRIANGLES, static_cast<GLint>(kConservativeVerticesPerTriangle * global),
                   static_cast<GLsizei>(kConservativeVerticesPerTriangle * count));
    else
      glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(3 * count), GL_UNSIGNED_INT,
                     indexOffset(global));
  }
  // Several runs of triangles of a mesh in one draw call.
  struct Run {
    std::uint32_t first = 0, count = 0;  // triangles of the mesh
  };
  void drawRuns(const GlMeshSlot& slot, std::span<const Run> runs);
  // Flags programs only: triangles k in [first, first + count) of a draw (a list's entries, with
  // FlagDraw::listed), and `instances` instances of a mesh (boxes, with FlagDraw::boxBase).
  // Large draws go as a multi-draw of segments: llvmpipe's vertex pipeline costs quadratically
  // in the vertices of one draw where any of them needs clipping (it resets the ids of all the
  // draw's vertices every time its small vertex buffer fills), and conservative triangles at the
  // viewport's border do. Segments change nothing for the shaders: in each draw of
  // glMultiDrawArrays gl_VertexID counts from that draw's `first`, as in one glDrawArrays.
  void drawNumbered(std::uint32_t first, std::uint32_t count) {
    if (count <= kSegmentTriangles) {
      const auto timed = drawTimer_.scope();
      glDrawArrays(GL_TRIANGLES, static_cast<GLint>(kConservativeVerticesPerTriangle * first),
                   static_cast<GLsizei>(kConservativeVerticesPerTriangle * count));
      return;
    }
    drawSegments(first, count);
  }
  void drawInstances(const GlMeshSlot& slot, std::uint32_t instances) {
    const auto timed = drawTimer_.scope();
    glDrawArraysInstanced(GL_TRIANGLES,
                          static_cast<GLint>(kConservativeVerticesPerTriangle * slot.firstTriangle),
                          static_cast<GLsizei>(kConservativeVerticesPerTriangle * slot.triangleCount),
                          static_cast<GLsizei>(instances));
  }

  // An order-independent pass' draw (Flags programs, in an order-independent pass): segments
  // [0, segmentTriangles.size()) of the table at `bases.segment` of the segment buffer, segment s
  // holding segmentTriangles[s] triangles (FlagShaders.h), drawn for `stage` with its buffers and
  // depth state; one multi-draw call.
  struct PassBases {
    std::int32_t segment = 0, listed = 0, box = 0;
  };
  void drawPass(PassStage stage, const PassBases& bases,
                std::span<const std::uint8_t> segmentTriangles);
  // Clears the order-independent pass' buffers again, as its beginPass did.
  void clearPassBuffers() { passTarget_.clear(static_cast<float>(setup_.clearDepth)); }

  std::uint32_t beginQuery() { return queries_.begin(); }
  void endQuery() { queries_.end(); }
  [[nodiscard]] std::size_t pendingQueries() const { return queries_.pending(); }
  void fetch(std::vector<std::uint8_t>& fullyVisible) { queries_.fetch(fullyVisible); }

  // Profiling (VisibilityOptions::timeGpu): the GPU time of the draws since the last collect;
  // call after a read-back.
  void timeDraws(bool on) { drawTimer_.enable(on); }
  std::uint64_t collectDrawNs() { return drawTimer_.enabled() ? drawTimer_.collectNs() : 0; }

 private:
  void applyPassState();
  void applyRole(DrawRole role);
  void applyLocal(const Eigen::Matrix4f& local, bool identity);
  void applyFlagDraw(const FlagDraw& draw);
  static constexpr std::uint32_t kSegmentTriangles = 32;
  void drawSegments(std::uint32_t first, std::uint32_t count);
  // Triangles are pulled from the storage buffers (no vertex array).
  [[nodiscard]] bool pulled() const { return conservative_ || programs_ == PipelinePrograms::Flags; }
  [[nodiscard]] GLuint programFor(DrawRole role) const {
    return program_[conservative_ ? 1 : 0][role == DrawRole::Test ? 1 : 0];
  }
  void useProgram(GLuint program);
  static const void* indexOffset(std::uint32_t globalTriangle) {
    return reinterpret_cast<const void*>(static_cast<std::uintptr_t>(globalTriangle) * 3u *
                                         sizeof(std::uint32_t));
  }
  void ensureTarget(int resolution);

  HeadlessGlContext* context_;
  PipelinePrograms programs_;
  std::vector<GlProgramName> ownedPrograms_;
  GLuint program_[2][2] = {};  // [conservative][test]: Queries uses one program for both roles
  GLuint passProgram_[2][3] = {};  // [conservative][PassStage], Flags only
  GLuint currentProgram_ = 0;
  GlFramebuffer framebuffer_;
  GlRenderbuffer depth_;
  int targetResolution_ = 0;
  int maxResolution_ = 0;
  GlSceneBuffers buffers_;
  GlQueryPool queries_;
  GlDrawTimer drawTimer_;
  GlPassTarget passTarget_;
  bool orderIndependent_ = false;  // the current pass

  bool conservative_ = true;
  double rawDepthOffset_ = 0.0;
  DepthPassSetup setup_;
  bool inPass_ = false;
  PassSequence sequence_;  // the SharedSecond rule (the backends check their own draws)
  // Cached draw state; reset by every pass.
  DrawRole role_ = DrawRole::None;
  std::vector<GLint> runFirsts_;
  std::vector<GLsizei> runCounts_;
  std::vector<const void*> runOffsets_;
  ObjectId object_ = ~ObjectId{0};
  bool localIdentity_ = false;
  FlagDraw flagDraw_;
  bool flagDrawSet_ = false;
};

}  // namespace cdb
