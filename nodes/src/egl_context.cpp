// Headless EGL context: surfaceless Mesa platform first (no display server, no environment
// variable), then the EGL device platform; OpenGL 4.5 core with no config and no surface.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <map>
#include <string>

#include "context_backends.h"

namespace aq {

namespace {

std::string egl_error_text(EGLint code) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "0x%04X", static_cast<unsigned>(code));
  return buffer;
}

// Live contexts per display (see ~EglContext).
std::map<EGLDisplay, int>& display_users() {
  static std::map<EGLDisplay, int> users;
  return users;
}

class EglContext final : public BackendContext {
 public:
  ~EglContext() override {
    if (display_ != EGL_NO_DISPLAY) {
      eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
      // The display is one per platform and process, shared by every context on it, and
      // eglTerminate is not reference counted: terminating it under another live context
      // would leave that one unable to be made current.
      if (--display_users()[display_] == 0) {
        display_users().erase(display_);
        eglTerminate(display_);
      }
    }
  }
  GlBackend backend() const override { return GlBackend::kEgl; }

  bool make_current() override {
    // Always rebind: an OSMesa context made current in between is invisible to EGL.
    return eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_) == EGL_TRUE;
  }
  void* get_proc_address(const char* name) const override {
    return reinterpret_cast<void*>(eglGetProcAddress(name));
  }

  Status init() {
    auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (get_platform_display == nullptr) {
      return make_error("eglGetPlatformDisplayEXT is missing (EGL_EXT_platform_base)");
    }
    display_ = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    EGLint major = 0, minor = 0;
    if (display_ == EGL_NO_DISPLAY || eglInitialize(display_, &major, &minor) != EGL_TRUE) {
      display_ = EGL_NO_DISPLAY;
      return make_error("no surfaceless EGL display (EGL_MESA_platform_surfaceless): " +
                        egl_error_text(eglGetError()));
    }
    ++display_users()[display_];
    if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) {
      return make_error("EGL cannot bind the desktop OpenGL API");
    }
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                 4,
                                 EGL_CONTEXT_MINOR_VERSION,
                                 5,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                 EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                 EGL_NONE};
    context_ = eglCreateContext(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    if (context_ == EGL_NO_CONTEXT) {
      return make_error("EGL refused an OpenGL 4.5 core context: " +
                        egl_error_text(eglGetError()));
    }
    if (!make_current()) return make_error("eglMakeCurrent failed");
    if (!load()) return make_error("the EGL context does not provide OpenGL 4.5 core functions");
    return Ok{};
  }

 private:
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

Result<std::unique_ptr<GlContext>> create_egl_context() {
  auto context = std::make_unique<EglContext>();
  if (auto status = context->init(); !status.ok()) return status.error();
  return std::unique_ptr<GlContext>(std::move(context));
}

}  // namespace aq
