// Headless EGL context, OpenGL 4.5 core with no config and no surface: on a hardware EGL
// device (EGL_EXT_platform_device) when there is one, else on Mesa's surfaceless platform (no
// display server, no environment variable; llvmpipe on a machine without a GPU).
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdlib>
#include <map>
#include <string>
#include <vector>

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

  // `display` from eglGetPlatformDisplayEXT; `what` names it in messages.
  Status init(EGLDisplay display, const std::string& what) {
    display_ = display;
    EGLint major = 0, minor = 0;
    if (display_ == EGL_NO_DISPLAY || eglInitialize(display_, &major, &minor) != EGL_TRUE) {
      display_ = EGL_NO_DISPLAY;
      return make_error("no EGL display for " + what + ": " + egl_error_text(eglGetError()));
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
      return make_error("EGL refused an OpenGL 4.5 core context: " + egl_error_text(eglGetError()));
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

namespace {

template <typename Function>
Function egl_function(const char* name) {
  return reinterpret_cast<Function>(eglGetProcAddress(name));
}

struct EglDevice {
  EGLDeviceEXT handle = nullptr;
  bool software = false;
  std::string description;
};

// The EGL devices (EGL_EXT_device_enumeration), in the driver's order.
std::vector<EglDevice> enumerate_devices() {
  auto query_devices = egl_function<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
  auto query_string = egl_function<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT");
  if (query_devices == nullptr || query_string == nullptr) return {};
  EGLint count = 0;
  if (query_devices(0, nullptr, &count) != EGL_TRUE || count <= 0) return {};
  std::vector<EGLDeviceEXT> handles(static_cast<size_t>(count));
  if (query_devices(count, handles.data(), &count) != EGL_TRUE) return {};
  std::vector<EglDevice> devices;
  for (EGLint i = 0; i < count; ++i) {
    EglDevice device;
    device.handle = handles[static_cast<size_t>(i)];
    const char* extensions = query_string(device.handle, EGL_EXTENSIONS);
    const std::string list = extensions != nullptr ? extensions : "";
    device.software = list.find("EGL_MESA_device_software") != std::string::npos;
    const char* file = list.find("EGL_EXT_device_drm") != std::string::npos
                           ? query_string(device.handle, EGL_DRM_DEVICE_FILE_EXT)
                           : nullptr;
    device.description = std::to_string(i) + ": " +
                         (file != nullptr ? std::string(file) : std::string("(no DRM node)")) +
                         (device.software ? " (software)" : " (hardware)");
    devices.push_back(device);
  }
  return devices;
}

Result<std::unique_ptr<GlContext>> context_on(EGLDisplay display, const std::string& what) {
  auto context = std::make_unique<EglContext>();
  if (auto status = context->init(display, what); !status.ok()) return status.error();
  return std::unique_ptr<GlContext>(std::move(context));
}

Result<std::unique_ptr<GlContext>> surfaceless_context() {
  auto get_platform_display =
      egl_function<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
  if (get_platform_display == nullptr) {
    return make_error("eglGetPlatformDisplayEXT is missing (EGL_EXT_platform_base)");
  }
  return context_on(
      get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
      "the surfaceless platform (EGL_MESA_platform_surfaceless)");
}

Result<std::unique_ptr<GlContext>> device_context(const EglDevice& device) {
  auto get_platform_display =
      egl_function<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
  if (get_platform_display == nullptr) {
    return make_error("eglGetPlatformDisplayEXT is missing (EGL_EXT_platform_base)");
  }
  return context_on(get_platform_display(EGL_PLATFORM_DEVICE_EXT, device.handle, nullptr),
                    "device " + device.description);
}

}  // namespace

std::vector<std::string> egl_device_descriptions() {
  std::vector<std::string> out;
  for (const EglDevice& device : enumerate_devices()) out.push_back(device.description);
  return out;
}

Result<std::unique_ptr<GlContext>> create_egl_context(const std::string& device) {
  if (device == "software") return surfaceless_context();
  const std::vector<EglDevice> devices = enumerate_devices();
  if (device.empty() || device == "auto") {
    // A hardware device when there is one; Mesa's surfaceless platform (llvmpipe on a machine
    // without a GPU) otherwise, or when the hardware one cannot give a 4.5 core context.
    for (const EglDevice& candidate : devices) {
      if (candidate.software) continue;
      auto context = device_context(candidate);
      if (context.ok()) return context;
    }
    return surfaceless_context();
  }
  std::string listed;
  for (const EglDevice& d : devices) listed += "\n    " + d.description;
  if (listed.empty()) listed = "\n    (none: this EGL cannot enumerate devices)";
  char* end = nullptr;
  const long index = std::strtol(device.c_str(), &end, 10);
  if (end == device.c_str() || *end != '\0' || index < 0 ||
      index >= static_cast<long>(devices.size())) {
    return make_error("GL device '" + device +
                      "' is not auto, software or the index of one of these EGL devices:" + listed);
  }
  return device_context(devices[static_cast<size_t>(index)]);
}

}  // namespace aq
