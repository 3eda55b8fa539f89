#include "culling/visibility/GlVisibilityPipeline.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <string>
#include <span>
#include <utility>

#include "core/Errors.h"
#include "culling/visibility/FlagShaders.h"
#include "render/HeadlessGlContext.h"

namespace cdb {

namespace u = occlusion_uniform;

GlVisibilityPipeline::GlVisibilityPipeline(HeadlessGlContext& context, PipelinePrograms programs)
    : context_(&context), programs_(programs) {
  context.makeCurrent();
  for (int conservative = 0; conservative < 2; ++conservative) {
    if (programs == PipelinePrograms::Queries) {
      ownedPrograms_.push_back(conservative ? makeConservativeOcclusionProgram()
                                            : makeRawOcclusionProgram());
      program_[conservative][0] = program_[conservative][1] = ownedPrograms_.back().get();
    } else {
      ownedPrograms_.push_back(makeFlagWriteProgram(conservative != 0));
      program_[conservative][0] = ownedPrograms_.back().get();
      ownedPrograms_.push_back(makeFlagTestProgram(conservative != 0));
      program_[conservative][1] = ownedPrograms_.back().get();
      for (PassStage stage : {PassStage::Nearest, PassStage::Others, PassStage::Test}) {
        ownedPrograms_.push_back(makePassProgram(stage, conservative != 0));
        passProgram_[conservative][static_cast<int>(stage)] = ownedPrograms_.back().get();
      }
    }
  }
  GLint renderbufferMax = 0, viewportMax[2] = {0, 0};
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &renderbufferMax);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewportMax);
  maxResolution_ = std::min({renderbufferMax, viewportMax[0], viewportMax[1]});
  GLuint name = 0;
  glCreateFramebuffers(1, &name);
  framebuffer_ = GlFramebuffer(name);
  // Depth only: nothing is shaded into colour.
  glNamedFramebufferDrawBuffer(framebuffer_.get(), GL_NONE);
  glNamedFramebufferReadBuffer(framebuffer_.get(), GL_NONE);
}

GlVisibilityPipeline::~GlVisibilityPipeline() {
  try {
    context_->makeCurrent();
  } catch (const RunError&) {
    // The context is gone or unusable: its objects went with it.
  }
}

void GlVisibilityPipeline::setConservative(bool conservative) {
  if (conservative == conservative_) return;
  conservative_ = conservative;
  if (inPass_) applyPassState();
}

void GlVisibilityPipeline::setRawDepthOffset(double ndcOffset) {
  rawDepthOffset_ = ndcOffset;
  if (inPass_) applyPassState();
}

void GlVisibilityPipeline::ensureTarget(int resolution) {
  if (resolution == targetResolution_) return;
  GLuint name = 0;
  glCreateRenderbuffers(1, &name);
  GlRenderbuffer depth(name);
  glNamedRenderbufferStorage(depth.get(), GL_DEPTH_COMPONENT32F, resolution, resolution);
  glNamedFramebufferRenderbuffer(framebuffer_.get(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                 depth.get());
  const GLenum status = glCheckNamedFramebufferStatus(framebuffer_.get(), GL_DRAW_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", status);
    throw RunError("the depth framebuffer of " + std::to_string(resolution) + "x" +
                   std::to_string(resolution) + " is incomplete (status " + code + ")");
  }
  depth_ = std::move(depth);
  targetResolution_ = resolution;
}

const GlMeshSlot& GlVisibilityPipeline::checkedSlot(ObjectId object) const {
  if (object >= buffers_.objectCount())
    throw RunError("object " + std::to_string(object) + " is not in the attached scene of " +
                   std::to_string(buffers_.objectCount()) + " objects");
  if (!inPass_) throw RunError("a visibility draw was issued outside a pass");
  return buffers_.slotOf(object);
}

void GlVisibilityPipeline::checkRange(const MeshRange& range) const {
  const GlMeshSlot& slot = checkedSlot(range.object);
  if (range.firstTriangle > slot.triangleCount ||
      range.triangleCount > slot.triangleCount - range.firstTriangle)
    throw RunError("triangles [" + std::to_string(range.firstTriangle) + ", +" +
                   std::to_string(range.triangleCount) + ") are outside object " +
                   std::to_string(range.object) + "'s " + std::to_string(slot.triangleCount));
}

DepthPassSetup GlVisibilityPipeline::beginCheckedPass(const ViewSpec& view, DepthUse depth) {
  if (depth == DepthUse::OrderIndependent && programs_ != PipelinePrograms::Flags)
    throw InputError("order-independent passes need the flag programs (gl-flags)");
  sequence_.checkBegin(view, depth);
  const DepthPassSetup setup = makeDepthPassSetup(view, depth);
  beginPass(setup, depth == DepthUse::OrderIndependent);
  sequence_.begin(view, depth);
  return setup;
}

void GlVisibilityPipeline::beginPass(const DepthPassSetup& setup, bool orderIndependent) {
  if (!buffers_.attached()) throw RunError("a visibility pass began before a scene was attached");
  if (setup.resolution < 1 || setup.resolution > maxResolution_)
    throw InputError("resolution " + std::to_string(setup.resolution) + " is outside 1.." +
                     std::to_string(maxResolution_) + " (the GL's largest framebuffer)");
  if (orderIndependent && programs_ != PipelinePrograms::Flags)
    throw InputError("order-independent passes need the flag programs (gl-flags)");
  if (orderIndependent)
    passTarget_.ensure(setup.resolution);
  else
    ensureTarget(setup.resolution);
  setup_ = setup;
  inPass_ = true;
  orderIndependent_ = orderIndependent;
  applyPassState();
  if (orderIndependent) {
    passTarget_.clear(static_cast<GLfloat>(setup.clearDepth));
    role_ = DrawRole::None;
  } else if (setup.clear) {
    glDepthMask(GL_TRUE);  // clears obey the depth write mask
    const auto value = static_cast<GLfloat>(setup.clearDepth);
    glClearBufferfv(GL_DEPTH, 0, &value);
    role_ = DrawRole::None;
  }
}

void GlVisibilityPipeline::applyPassState() {
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER,
                    orderIndependent_ ? passTarget_.nearestFramebuffer() : framebuffer_.get());
  glViewport(0, 0, setup_.resolution, setup_.resolution);
  glEnable(GL_DEPTH_TEST);
  // Depths are clamped into the pass' part of the range: geometry beyond the near or far plane is
  // kept instead of clipped away, and conservative epsilons never reach the other pass' half.
  glEnable(GL_DEPTH_CLAMP);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  glDepthRange(setup_.depthNear, setup_.depthFar);
  buffers_.bind(pulled());
  const Eigen::Matrix4f worldToScreen = setup_.worldToScreen.cast<float>();
  const Eigen::Matrix4f worldToClip = setup_.worldToClip.cast<float>();
  const GLuint* roles = program_[conservative_ ? 1 : 0];
  const GLuint* stages = passProgram_[conservative_ ? 1 : 0];
  // Each program once (Queries: one for both roles; no pass programs), with the side it draws
  // for: +1 tests, -1 writes.
  std::pair<GLuint, bool> programs[5];
  std::size_t count = 0;
  programs[count++] = {roles[0], false};
  if (roles[1] != roles[0]) programs[count++] = {roles[1], true};
  if (stages[0] != 0)
    for (PassStage stage : {PassStage::Nearest, PassStage::Others, PassStage::Test})
      programs[count++] = {stages[static_cast<int>(stage)], stage == PassStage::Test};
  for (const auto& [program, test] : std::span(programs, count)) {
    if (conservative_) {
      glProgramUniformMatrix4fv(program, u::kWorldTo, 1, GL_FALSE, worldToScreen.data());
      // The epsilon is in stored-depth units; the shader works in view depth t.
      glProgramUniform1f(program, u::kDepthEpsilon,
                         static_cast<float>(setup_.depthEpsilon /
                                            std::abs(setup_.depthFar - setup_.depthNear)));
      glProgramUniform1f(program, u::kGrowPx, static_cast<float>(0.5 + setup_.coverageMarginPx));
      glProgramUniform1f(program, u::kResolution, static_cast<float>(setup_.resolution));
      glProgramUniform1f(program, u::kSide, test ? 1.f : -1.f);
    } else {
      glProgramUniformMatrix4fv(program, u::kWorldTo, 1, GL_FALSE, worldToClip.data());
      glProgramUniform1f(program, u::kNdcOffset, test ? static_cast<float>(rawDepthOffset_) : 0.f);
    }
  }
  currentProgram_ = 0;
  useProgram(programFor(DrawRole::Write));
  role_ = DrawRole::None;
}

void GlVisibilityPipeline::useProgram(GLuint program) {
  if (program == currentProgram_) return;
  glUseProgram(program);
  currentProgram_ = program;
  // Uniforms are the program's own: what is cached was set on another one.
  object_ = ~ObjectId{0};
  localIdentity_ = false;
  flagDrawSet_ = false;
}

void GlVisibilityPipeline::applyRole(DrawRole role) {
  useProgram(programFor(role));
  const bool reversed = setup_.reversed();
  if (role == DrawRole::Test) {
    // At or behind what is stored = occluded; nothing of the test is stored.
    glDepthMask(GL_FALSE);
    glDepthFunc(reversed ? GL_LEQUAL : GL_GEQUAL);
  } else {
    glDepthMask(GL_TRUE);
    glDepthFunc(reversed ? GL_GREATER : GL_LESS);
  }
  if (conservative_)
    glUniform1f(u::kSide, role == DrawRole::Test ? 1.f : -1.f);
  else
    glUniform1f(u::kNdcOffset, role == DrawRole::Test ? static_cast<float>(rawDepthOffset_) : 0.f);
  role_ = role;
}

void GlVisibilityPipeline::applyLocal(const Eigen::Matrix4f& local, bool identity) {
  glUniformMatrix4fv(u::kLocal, 1, GL_FALSE, local.data());
  localIdentity_ = identity;
}

void GlVisibilityPipeline::applyFlagDraw(const FlagDraw& draw) {
  namespace f = flag_uniform;
  glUniform1i(f::kItemBase, draw.itemBase);
  glUniform1i(f::kItemPerTriangle, draw.itemPerTriangle ? 1 : 0);
  glUniform1i(f::kListed, draw.listed ? 1 : 0);
  glUniform1i(f::kBoxBase, draw.boxBase);
  flagDraw_ = draw;
  flagDrawSet_ = true;
}

void GlVisibilityPipeline::drawPass(PassStage stage, const PassBases& bases,
                                    std::span<const std::uint8_t> segmentTriangles) {
  useProgram(passProgram_[conservative_ ? 1 : 0][static_cast<int>(stage)]);
  passTarget_.bindFor(stage);
  glEnable(GL_DEPTH_TEST);
  if (stage == PassStage::Test) {
    // A Fresh pass' test against d1 (applyRole): at or behind = occluded, nothing stored.
    glDepthMask(GL_FALSE);
    glDepthFunc(GL_GEQUAL);
  } else {
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
  }
  namespace p = pass_uniform;
  glUniform1i(p::kSegmentBase, bases.segment);
  glUniform1i(p::kListedBase, bases.listed);
  glUniform1i(p::kBoxBase, bases.box);
  constexpr GLint kSegmentVertices = kConservativeVerticesPerTriangle * kPassSegmentTriangles;
  if (segmentTriangles.size() > static_cast<std::size_t>(INT32_MAX / kSegmentVertices))
    throw RunError("an order-independent draw of " + std::to_string(segmentTriangles.size()) +
                   " segments is too large for one draw");
  runFirsts_.clear();
  runCounts_.clear();
  for (std::size_t s = 0; s < segmentTriangles.size(); ++s) {
    runFirsts_.push_back(static_cast<GLint>(kSegmentVertices * s));
    runCounts_.push_back(static_cast<GLsizei>(kConservativeVerticesPerTriangle * segmentTriangles[s]));
  }
  const auto timed = drawTimer_.scope();
  glMultiDrawArrays(GL_TRIANGLES, runFirsts_.data(), runCounts_.data(),
                    static_cast<GLsizei>(runFirsts_.size()));
  // The next role-based draw sets its state again.
  role_ = DrawRole::None;
}

void GlVisibilityPipeline::drawSegments(std::uint32_t first, std::uint32_t count) {
  runFirsts_.clear();
  runCounts_.clear();
  for (std::uint32_t done = 0; done < count; done += kSegmentTriangles) {
    runFirsts_.push_back(static_cast<GLint>(kConservativeVerticesPerTriangle * (first + done)));
    runCounts_.push_back(static_cast<GLsizei>(kConservativeVerticesPerTriangle *
                                              std::min(kSegmentTriangles, count - done)));
  }
  const auto timed = drawTimer_.scope();
  glMultiDrawArrays(GL_TRIANGLES, runFirsts_.data(), runCounts_.data(),
                    static_cast<GLsizei>(runFirsts_.size()));
}

void GlVisibilityPipeline::drawRuns(const GlMeshSlot& slot, std::span<const Run> runs) {
  const auto timed = drawTimer_.scope();
  runCounts_.clear();
  if (pulled()) {
    runFirsts_.clear();
    for (const Run& r : runs) {
      runFirsts_.push_back(
          static_cast<GLint>(kConservativeVerticesPerTriangle * (slot.firstTriangle + r.first)));
      runCounts_.push_back(static_cast<GLsizei>(kConservativeVerticesPerTriangle * r.count));
    }
    glMultiDrawArrays(GL_TRIANGLES, runFirsts_.data(), runCounts_.data(),
                      static_cast<GLsizei>(runs.size()));
  } else {
    runOffsets_.clear();
    for (const Run& r : runs) {
      runOffsets_.push_back(indexOffset(slot.firstTriangle + r.first));
      runCounts_.push_back(static_cast<GLsizei>(3 * r.count));
    }
    glMultiDrawElements(GL_TRIANGLES, runCounts_.data(), GL_UNSIGNED_INT, runOffsets_.data(),
                        static_cast<GLsizei>(runs.size()));
  }
}

}  // namespace cdb
