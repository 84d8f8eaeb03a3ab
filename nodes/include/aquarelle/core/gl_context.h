// Headless and windowed OpenGL contexts. EGL surfaceless is the default headless backend,
// OSMesa the fallback; an external context (the editor's GLFW window) can be adopted. Each
// gives 4.5 core on Mesa llvmpipe. There is no default framebuffer: always render to FBOs.
#pragma once

#include <aquarelle/core/result.h>

#include <memory>
#include <string>
#include <vector>

namespace aq {

enum class GlBackend { kAuto, kEgl, kOsmesa, kExternal };

const char* backend_name(GlBackend backend);
// "auto" | "egl" | "osmesa"; nullopt-like error for anything else.
Result<GlBackend> parse_backend(const std::string& name);

class GlContext {
 public:
  GlContext();
  virtual ~GlContext();
  virtual GlBackend backend() const = 0;
  virtual bool make_current() = 0;
  // Makes this context current and, when another context's functions were loaded last,
  // reloads the core's GL functions (and bumps generation()). Use before any GL work.
  bool activate();
  virtual void* get_proc_address(const char* name) const = 0;
  // "OpenGL 4.5 (Core Profile) Mesa 22.3.6, llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string description() const;
  // Changes every time a context is made current through a different backend, so plugins know
  // to reload their GL functions.
  uint32_t generation() const { return generation_; }

 protected:
  uint32_t generation_ = 0;
  uint64_t serial_;  // unique per context ever made: addresses of dead contexts get reused
  // Loads the core's glad from this context; call after making it current.
  bool load_functions();
};

// Creates a headless context. kAuto tries EGL, then OSMesa; when none works the message says
// what each attempt said. `device` picks the EGL device: "auto" takes a hardware device (a GPU)
// when EGL lists one and Mesa's surfaceless platform (llvmpipe) otherwise; "software" always
// the latter; a number the EGL device with that index (see egl_device_descriptions). OSMesa
// ignores it.
Result<std::unique_ptr<GlContext>> create_headless_context(GlBackend backend,
                                                           const std::string& device = "auto");

// Whether `device` is a well-formed device choice (auto, software or a number), with a message
// saying what is accepted when not; whether a number names a device is known only at creation.
Status check_gl_device(const std::string& device);

// "0: /dev/dri/renderD128 (hardware)", one per EGL device, for --gl-device and its messages.
std::vector<std::string> egl_device_descriptions();

// Adopts a context that something else (GLFW) created and made current.
std::unique_ptr<GlContext> adopt_current_context(void* (*get_proc_address)(const char*));

}  // namespace aq
