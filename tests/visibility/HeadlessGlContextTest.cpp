#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "core/Errors.h"
#include "render/Gl.h"
#include "render/HeadlessGlContext.h"
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

TEST(HeadlessGlContext, DevicePlatformOpensTheDeviceAutoFindsOrSaysWhy) {
  // Auto tries the hardware EGL devices first, best first, as the device platform does; the device
  // platform then also tries Mesa's software device. So where auto lands on a device, the device
  // platform opens that same renderer; where it does not (no GPU), the device platform opens a
  // software renderer or fails with a one-line RunError that names the platform.
  const GlInfo automatic = HeadlessGlContext(GlPlatform::Auto).info();
  std::string renderer, failure;
  try {
    HeadlessGlContext context(GlPlatform::Device);
    EXPECT_EQ(context.info().platform, "device");
    expectUsable(context);
    renderer = context.info().glRenderer;
  } catch (const RunError& e) {
    failure = e.what();
  }
  if (automatic.platform == "device") {
    EXPECT_EQ(failure, "") << "auto opened a device, the device platform did not";
    EXPECT_EQ(renderer, automatic.glRenderer);
  } else if (failure.empty()) {
    const bool software = renderer.find("llvmpipe") != std::string::npos ||
                          renderer.find("softpipe") != std::string::npos;
    EXPECT_TRUE(software) << "auto found no hardware device, yet the device platform opened "
                          << renderer;
  } else {
    EXPECT_EQ(failure.find('\n'), std::string::npos) << failure;
    EXPECT_NE(failure.find("device"), std::string::npos) << failure;
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

// Runs `platform` in a fresh child process with `variable` set (EGL reads its environment once,
// at start-up) and expects a one-line RunError that starts with `expected`.
void expectOpenFailure(const char* variable, const char* value, GlPlatform platform,
                       const std::string& expected) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  setenv(variable, value, 1);
  EXPECT_EXIT(
      {
        try {
          HeadlessGlContext context(platform);
          std::exit(3);
        } catch (const RunError& e) {
          const std::string what = e.what();
          std::fprintf(stderr, "%s\n", what.c_str());
          std::exit(what.rfind(expected, 0) == 0 && what.find('\n') == std::string::npos ? 0 : 4);
        }
      },
      testing::ExitedWithCode(0), "");  // exit code 0: the child matched `expected`
  unsetenv(variable);
}

TEST(HeadlessGlContextDeathTest, NoDisplayIsAOneLineRunErrorWithAHint) {
  // glvnd then finds no EGL vendor at all.
  expectOpenFailure("__EGL_VENDOR_LIBRARY_FILENAMES", "/nonexistent/egl_vendor.json",
                    GlPlatform::Auto,
                    "no EGL display could be opened (tried device, surfaceless, default): install");
}

TEST(HeadlessGlContextDeathTest, OldOpenGlIsAOneLineRunError) {
  // The death-test child re-runs this body with the override set; only the parent looks at the GL.
  const bool inChild = std::getenv("MESA_GL_VERSION_OVERRIDE") != nullptr;
  if (!inChild && test::sharedGlContext().info().glVersion.find("Mesa") == std::string::npos)
    GTEST_SKIP() << "needs Mesa, whose version override stands in for an old driver";
  expectOpenFailure("MESA_GL_VERSION_OVERRIDE", "3.3", GlPlatform::Surfaceless,
                    "OpenGL 4.5 core is not available (got 3.3");
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
