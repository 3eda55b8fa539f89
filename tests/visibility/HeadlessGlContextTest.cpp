#include "render/HeadlessGlContext.h"

#include <iostream>

#include <gtest/gtest.h>

#include "core/Errors.h"
#include "render/Gl.h"
#include "tests/visibility/GlTestSupport.h"

namespace cdb {
namespace {

void expectUsable(const HeadlessGlContext& context) {
  const GlInfo& info = context.info();
  std::cout << "[ GL      ] platform " << info.platform << ", EGL " << info.eglVendor << " "
            << info.eglVersion << ", " << info.glRenderer << " (" << info.glVendor << "), "
            << info.glVersion << "\n";
  EXPECT_FALSE(info.glRenderer.empty());
  EXPECT_FALSE(info.glVersion.empty());
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  EXPECT_GE(major * 10 + minor, 45);
  GLint profile = 0;
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
}

TEST(HeadlessGlContext, OpensWithAuto) {
  HeadlessGlContext context(GlPlatform::Auto);
  expectUsable(context);
}

TEST(HeadlessGlContext, OpensSurfaceless) {
  HeadlessGlContext context(GlPlatform::Surfaceless);
  EXPECT_EQ(context.info().platform, "surfaceless");
  expectUsable(context);
}

TEST(HeadlessGlContext, DevicePlatformOpensOrSaysWhy) {
  // Mesa lists its software rasteriser as an EGL device, so this usually opens; where it does not,
  // the error is one line with a hint.
  try {
    HeadlessGlContext context(GlPlatform::Device);
    EXPECT_EQ(context.info().platform, "device");
    expectUsable(context);
  } catch (const RunError& e) {
    const std::string what = e.what();
    std::cout << "[ GL      ] device platform: " << what << "\n";
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
}

TEST(HeadlessGlContext, TwoContextsCoexist) {
  // Both share the surfaceless display; closing one must leave the other usable.
  HeadlessGlContext& shared = test::sharedGlContext();
  {
    HeadlessGlContext other(GlPlatform::Surfaceless);
    other.makeCurrent();
  }
  shared.makeCurrent();
  EXPECT_NE(glGetString(GL_RENDERER), nullptr);
}

TEST(GlPlatformParse, KnownNames) {
  EXPECT_EQ(parseGlPlatform("auto"), GlPlatform::Auto);
  EXPECT_EQ(parseGlPlatform("device"), GlPlatform::Device);
  EXPECT_EQ(parseGlPlatform("surfaceless"), GlPlatform::Surfaceless);
  for (GlPlatform p : {GlPlatform::Auto, GlPlatform::Device, GlPlatform::Surfaceless})
    EXPECT_EQ(parseGlPlatform(toString(p)), p);
}

TEST(GlPlatformParse, BadNameIsInputError) {
  EXPECT_THROW((void)parseGlPlatform("x11"), InputError);
  EXPECT_THROW((void)parseGlPlatform(""), InputError);
  EXPECT_THROW((void)parseGlPlatform("Auto"), InputError);
}

}  // namespace
}  // namespace cdb
