#include "culling/visibility/GlPassTarget.h"

#include <cstdio>
#include <string>

#include "core/Errors.h"

namespace cdb {

namespace {

GlTexture texture2D(GLenum format, int resolution) {
  GLuint name = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &name);
  GlTexture texture(name);
  glTextureStorage2D(texture.get(), 1, format, resolution, resolution);
  // Read with texelFetch only; a single level with these filters is complete.
  glTextureParameteri(texture.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return texture;
}

GlFramebuffer framebuffer() {
  GLuint name = 0;
  glCreateFramebuffers(1, &name);
  return GlFramebuffer(name);
}

void checkComplete(GLuint fb, const char* what, int resolution) {
  const GLenum status = glCheckNamedFramebufferStatus(fb, GL_DRAW_FRAMEBUFFER);
  if (status == GL_FRAMEBUFFER_COMPLETE) return;
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", status);
  throw RunError(std::string("the ") + what + " framebuffer of " + std::to_string(resolution) +
                 "x" + std::to_string(resolution) + " is incomplete (status " + code + ")");
}

}  // namespace

void GlPassTarget::ensure(int resolution) {
  if (resolution == resolution_) return;
  GlTexture nearestDepth = texture2D(GL_DEPTH_COMPONENT32F, resolution);
  GlTexture nearestObject = texture2D(GL_R32UI, resolution);
  GlTexture othersDepth = texture2D(GL_DEPTH_COMPONENT32F, resolution);
  GlFramebuffer nearest = framebuffer(), others = framebuffer(), tests = framebuffer();
  glNamedFramebufferTexture(nearest.get(), GL_DEPTH_ATTACHMENT, nearestDepth.get(), 0);
  glNamedFramebufferTexture(nearest.get(), GL_COLOR_ATTACHMENT0, nearestObject.get(), 0);
  glNamedFramebufferDrawBuffer(nearest.get(), GL_COLOR_ATTACHMENT0);
  glNamedFramebufferReadBuffer(nearest.get(), GL_NONE);
  glNamedFramebufferTexture(others.get(), GL_DEPTH_ATTACHMENT, othersDepth.get(), 0);
  glNamedFramebufferDrawBuffer(others.get(), GL_NONE);
  glNamedFramebufferReadBuffer(others.get(), GL_NONE);
  glNamedFramebufferTexture(tests.get(), GL_DEPTH_ATTACHMENT, nearestDepth.get(), 0);
  glNamedFramebufferDrawBuffer(tests.get(), GL_NONE);
  glNamedFramebufferReadBuffer(tests.get(), GL_NONE);
  checkComplete(nearest.get(), "nearest-depth", resolution);
  checkComplete(others.get(), "others-depth", resolution);
  checkComplete(tests.get(), "pass test", resolution);
  nearestDepth_ = std::move(nearestDepth);
  nearestObject_ = std::move(nearestObject);
  othersDepth_ = std::move(othersDepth);
  nearest_ = std::move(nearest);
  others_ = std::move(others);
  tests_ = std::move(tests);
  resolution_ = resolution;
}

void GlPassTarget::clear(float depth) {
  // Clears obey the write masks.
  glDepthMask(GL_TRUE);
  glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  const GLuint none[4] = {kNoObject, 0, 0, 0};
  glClearNamedFramebufferfv(nearest_.get(), GL_DEPTH, 0, &depth);
  glClearNamedFramebufferuiv(nearest_.get(), GL_COLOR, 0, none);
  glClearNamedFramebufferfv(others_.get(), GL_DEPTH, 0, &depth);
}

void GlPassTarget::bindFor(PassStage stage) const {
  switch (stage) {
    case PassStage::Nearest:
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, nearest_.get());
      break;
    case PassStage::Others:
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, others_.get());
      glBindTextureUnit(kNearestObjectUnit, nearestObject_.get());
      break;
    case PassStage::Test:
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, tests_.get());
      glBindTextureUnit(kNearestObjectUnit, nearestObject_.get());
      glBindTextureUnit(kOthersDepthUnit, othersDepth_.get());
      break;
  }
}

}  // namespace cdb
