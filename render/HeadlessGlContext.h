#pragma once
// A window-less OpenGL 4.5 core context through EGL. This is the only module that touches EGL:
// Mesa's surfaceless platform (llvmpipe) runs on any Linux machine, the EGL device platform reaches
// a GPU (NVIDIA or a Mesa DRM driver) without a display server. Rendering goes to framebuffer
// objects only; the context has no default framebuffer (EGL_KHR_surfaceless_context).
#include <memory>
#include <string>
#include <string_view>

namespace cdb {

enum class GlPlatform {
  Auto,         // a hardware EGL device if there is one, else surfaceless, else the default display
  Device,       // EGL_EXT_platform_device: a hardware device first, a software one otherwise
  Surfaceless,  // EGL_MESA_platform_surfaceless (llvmpipe without a GPU)
};

// "auto", "device" or "surfaceless"; anything else is an InputError.
[[nodiscard]] GlPlatform parseGlPlatform(std::string_view text);
[[nodiscard]] std::string_view toString(GlPlatform platform);

// What a result folder records about the renderer.
struct GlInfo {
  std::string platform;  // the platform that was opened: "device", "surfaceless" or "default"
  std::string eglVendor, eglVersion;
  std::string glVendor, glRenderer, glVersion;
};

class HeadlessGlContext {
 public:
  // Opens a display, creates the context and makes it current on this thread. Throws RunError
  // (one line with a hint) when no display opens or OpenGL 4.5 core is not available.
  explicit HeadlessGlContext(GlPlatform platform = GlPlatform::Auto);
  ~HeadlessGlContext();
  HeadlessGlContext(const HeadlessGlContext&) = delete;
  HeadlessGlContext& operator=(const HeadlessGlContext&) = delete;

  // Makes the context current on the calling thread (GL objects belong to this context).
  void makeCurrent() const;
  [[nodiscard]] const GlInfo& info() const { return info_; }

 private:
  struct Egl;  // EGL handles, kept out of this header so nothing else includes EGL
  std::unique_ptr<Egl> egl_;
  GlInfo info_;
};

}  // namespace cdb
