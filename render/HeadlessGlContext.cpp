#include "render/HeadlessGlContext.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/Errors.h"
#include "render/Gl.h"

namespace cdb {

namespace {

constexpr const char* kInstallHint =
    "install Mesa's EGL (apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri)";
constexpr int kMajor = 4;
constexpr int kMinor = 5;

bool hasExtension(const char* list, std::string_view name) {
  if (list == nullptr) return false;
  const std::string_view all(list);
  for (std::size_t pos = 0; (pos = all.find(name, pos)) != std::string_view::npos;
       pos += name.size()) {
    const bool startOk = pos == 0 || all[pos - 1] == ' ';
    const std::size_t end = pos + name.size();
    if (startOk && (end == all.size() || all[end] == ' ')) return true;
  }
  return false;
}

template <class Fn>
Fn eglProc(const char* name) {
  return reinterpret_cast<Fn>(eglGetProcAddress(name));
}

std::string eglErrorText() {
  const EGLint e = eglGetError();
  switch (e) {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    default: {
      char buf[32];
      std::snprintf(buf, sizeof buf, "EGL error 0x%04x", static_cast<unsigned>(e));
      return buf;
    }
  }
}

// eglTerminate ends a display for every context on it, and the same platform yields the same
// display handle, so displays are terminated only when their last user goes.
class DisplayUsers {
 public:
  static void acquire(EGLDisplay d) {
    std::lock_guard lock(mutex());
    ++counts()[d];
  }
  static void release(EGLDisplay d) {
    std::lock_guard lock(mutex());
    auto it = counts().find(d);
    if (it == counts().end()) return;
    if (--it->second == 0) {
      counts().erase(it);
      eglTerminate(d);
    }
  }

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  static std::map<EGLDisplay, int>& counts() {
    static std::map<EGLDisplay, int> c;
    return c;
  }
};

struct Candidate {
  std::string platform;  // "device", "surfaceless", "default"
  EGLenum eglPlatform = 0;
  void* native = nullptr;  // EGLDeviceEXT for the device platform
};

// Lower is preferred: NVIDIA (CUDA-capable), then other devices with a DRM render node, then other
// hardware, then Mesa's software rasteriser.
int deviceRank(EGLDeviceEXT device) {
  auto queryString = eglProc<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT");
  const char* ext = queryString != nullptr ? queryString(device, EGL_EXTENSIONS) : nullptr;
  if (hasExtension(ext, "EGL_MESA_device_software")) return 3;
  if (hasExtension(ext, "EGL_NV_device_cuda")) return 0;
  if (hasExtension(ext, "EGL_EXT_device_drm_render_node")) return 1;
  return 2;
}

// EGL devices split into hardware (best first) and software (Mesa's llvmpipe device).
void enumerateDevices(std::vector<EGLDeviceEXT>& hardware, std::vector<EGLDeviceEXT>& software) {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!hasExtension(client, "EGL_EXT_platform_device")) return;
  auto queryDevices = eglProc<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
  if (queryDevices == nullptr) return;
  EGLint count = 0;
  if (queryDevices(0, nullptr, &count) != EGL_TRUE || count <= 0) return;
  std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
  if (queryDevices(count, devices.data(), &count) != EGL_TRUE) return;
  devices.resize(static_cast<std::size_t>(count));
  std::vector<std::pair<int, EGLDeviceEXT>> ranked;
  for (EGLDeviceEXT d : devices) ranked.emplace_back(deviceRank(d), d);
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [rank, d] : ranked) (rank == 3 ? software : hardware).push_back(d);
}

std::vector<Candidate> candidatesFor(GlPlatform platform) {
  std::vector<EGLDeviceEXT> hardware, software;
  if (platform != GlPlatform::Surfaceless) enumerateDevices(hardware, software);
  std::vector<Candidate> out;
  for (EGLDeviceEXT d : hardware) out.push_back({"device", EGL_PLATFORM_DEVICE_EXT, d});
  if (platform == GlPlatform::Device) {
    for (EGLDeviceEXT d : software) out.push_back({"device", EGL_PLATFORM_DEVICE_EXT, d});
    if (out.empty())
      out.push_back({"device", EGL_PLATFORM_DEVICE_EXT, nullptr});  // reported as failed
    return out;
  }
  out.push_back({"surfaceless", EGL_PLATFORM_SURFACELESS_MESA, nullptr});
  if (platform == GlPlatform::Auto) out.push_back({"default", 0, nullptr});
  return out;
}

EGLDisplay openDisplay(const Candidate& c) {
  if (c.platform == "default") return eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (c.platform == "device" && c.native == nullptr) return EGL_NO_DISPLAY;
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (c.platform == "surfaceless" && !hasExtension(client, "EGL_MESA_platform_surfaceless"))
    return EGL_NO_DISPLAY;
  auto getPlatformDisplay = eglProc<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
  if (getPlatformDisplay == nullptr) return EGL_NO_DISPLAY;
  return getPlatformDisplay(c.eglPlatform, c.native, nullptr);
}

std::optional<EGLConfig> chooseConfig(EGLDisplay display) {
  // No config is needed for a surfaceless context where the display allows it.
  if (hasExtension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_no_config_context"))
    return EGL_NO_CONFIG_KHR;
  for (EGLint surfaceType : {EGLint{EGL_PBUFFER_BIT}, EGLint{0}}) {
    const EGLint attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, surfaceType,
                              EGL_NONE};
    EGLConfig config = nullptr;
    EGLint n = 0;
    if (eglChooseConfig(display, attribs, &config, 1, &n) == EGL_TRUE && n > 0) return config;
  }
  return std::nullopt;
}

EGLContext createContext(EGLDisplay display, EGLConfig config, int major, int minor, bool debug) {
  std::vector<EGLint> attribs;
  if (major > 0) {
    attribs = {EGL_CONTEXT_MAJOR_VERSION_KHR,       major,
               EGL_CONTEXT_MINOR_VERSION_KHR,       minor,
               EGL_CONTEXT_OPENGL_PROFILE_MASK_KHR, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT_KHR};
    if (debug)
      attribs.insert(attribs.end(), {EGL_CONTEXT_FLAGS_KHR, EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR});
  }
  attribs.push_back(EGL_NONE);
  return eglCreateContext(display, config, EGL_NO_CONTEXT, attribs.data());
}

// The best version a display offers, for the message when 4.5 core is missing.
std::string probeVersion(EGLDisplay display, EGLConfig config) {
  const int versions[][2] = {{4, 4}, {4, 3}, {4, 2}, {4, 1}, {4, 0}, {3, 3}, {3, 2}, {0, 0}};
  for (const auto& v : versions) {
    EGLContext ctx = createContext(display, config, v[0], v[1], false);
    if (ctx == EGL_NO_CONTEXT) continue;
    std::string got = "none";
    if (eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx) == EGL_TRUE) {
      const auto* s = reinterpret_cast<const char*>(glGetString(GL_VERSION));
      if (s != nullptr) got = s;
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
    eglDestroyContext(display, ctx);
    return got;
  }
  return "no OpenGL context at all";
}

#ifndef NDEBUG
void APIENTRY onGlDebugMessage(GLenum, GLenum type, GLuint, GLenum severity, GLsizei,
                               const GLchar* message, const void*) {
  if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
  std::fprintf(stderr, "GL debug (%s): %s\n", type == GL_DEBUG_TYPE_ERROR ? "error" : "warning",
               message);
}
#endif

std::string glString(GLenum name) {
  const auto* s = reinterpret_cast<const char*>(glGetString(name));
  return s != nullptr ? s : "";
}

std::string_view triedList(GlPlatform platform) {
  switch (platform) {
    case GlPlatform::Auto:
      return "device, surfaceless, default";
    case GlPlatform::Device:
      return "device";
    case GlPlatform::Surfaceless:
      return "surfaceless";
  }
  return "";
}

}  // namespace

GlPlatform parseGlPlatform(std::string_view text) {
  if (text == "auto") return GlPlatform::Auto;
  if (text == "device") return GlPlatform::Device;
  if (text == "surfaceless") return GlPlatform::Surfaceless;
  throw InputError("unknown GL platform '" + std::string(text) +
                   "': expected auto, device or surfaceless");
}

std::string_view toString(GlPlatform platform) {
  switch (platform) {
    case GlPlatform::Auto:
      return "auto";
    case GlPlatform::Device:
      return "device";
    case GlPlatform::Surfaceless:
      return "surfaceless";
  }
  return "auto";
}

struct HeadlessGlContext::Egl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
};

HeadlessGlContext::HeadlessGlContext(GlPlatform platform) : egl_(std::make_unique<Egl>()) {
#ifndef NDEBUG
  constexpr bool debug = true;
#else
  constexpr bool debug = false;
#endif
  const std::vector<Candidate> candidates = candidatesFor(platform);
  bool anyDisplay = false;
  std::string versionProblem;  // first display that opened but could not give 4.5 core
  for (const Candidate& c : candidates) {
    EGLDisplay display = openDisplay(c);
    if (display == EGL_NO_DISPLAY) continue;
    EGLint major = 0, minor = 0;
    if (eglInitialize(display, &major, &minor) != EGL_TRUE) continue;
    DisplayUsers::acquire(display);
    anyDisplay = true;
    const auto fail = [&](std::string why) {
      if (versionProblem.empty()) versionProblem = std::move(why);
      DisplayUsers::release(display);
    };
    if (!hasExtension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context")) {
      fail("the " + c.platform + " EGL display lacks EGL_KHR_surfaceless_context");
      continue;
    }
    if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) {
      fail("the " + c.platform + " EGL display has no desktop OpenGL (" + eglErrorText() + ")");
      continue;
    }
    const std::optional<EGLConfig> config = chooseConfig(display);
    if (!config) {
      fail("the " + c.platform + " EGL display has no OpenGL config");
      continue;
    }
    EGLContext context = createContext(display, *config, kMajor, kMinor, debug);
    if (context == EGL_NO_CONTEXT) {
      fail("OpenGL 4.5 core is not available (got " + probeVersion(display, *config) + " on the " +
           c.platform + " platform)");
      continue;
    }
    if (eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context) != EGL_TRUE) {
      const std::string why = eglErrorText();
      eglDestroyContext(display, context);
      fail("a surfaceless OpenGL context could not be made current on the " + c.platform +
           " platform (" + why + ")");
      continue;
    }
    GLint glMajor = 0, glMinor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &glMajor);
    glGetIntegerv(GL_MINOR_VERSION, &glMinor);
    if (glMajor * 10 + glMinor < kMajor * 10 + kMinor) {
      const std::string got = glString(GL_VERSION);
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      eglDestroyContext(display, context);
      fail("OpenGL 4.5 core is not available (got " + got + " on the " + c.platform + " platform)");
      continue;
    }
    egl_->display = display;
    egl_->context = context;
    info_.platform = c.platform;
    const char* vendor = eglQueryString(display, EGL_VENDOR);
    const char* version = eglQueryString(display, EGL_VERSION);
    info_.eglVendor = vendor != nullptr ? vendor : "";
    info_.eglVersion = version != nullptr ? version : "";
    info_.glVendor = glString(GL_VENDOR);
    info_.glRenderer = glString(GL_RENDERER);
    info_.glVersion = glString(GL_VERSION);
#ifndef NDEBUG
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(onGlDebugMessage, nullptr);
#endif
    return;
  }
  if (!anyDisplay) {
    throw RunError("no EGL display could be opened (tried " + std::string(triedList(platform)) +
                   "): " + kInstallHint);
  }
  throw RunError(
      versionProblem +
      ": use a GPU driver with OpenGL 4.5, or Mesa >= 20.3 whose llvmpipe provides it on "
      "the surfaceless platform");
}

HeadlessGlContext::~HeadlessGlContext() {
  if (egl_->context == EGL_NO_CONTEXT) return;
  if (eglGetCurrentContext() == egl_->context)
    eglMakeCurrent(egl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(egl_->display, egl_->context);
  DisplayUsers::release(egl_->display);
}

void HeadlessGlContext::makeCurrent() const {
  if (eglGetCurrentContext() == egl_->context) return;
  if (eglMakeCurrent(egl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, egl_->context) != EGL_TRUE)
    throw RunError("the OpenGL context could not be made current (" + eglErrorText() + ")");
}

}  // namespace cdb
