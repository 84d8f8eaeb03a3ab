// GlContext: backend selection and what every backend shares (glad loading, description).
// The EGL backend lives in egl_context.cpp and OSMesa in osmesa_context.cpp (its header pulls
// <GL/gl.h>, which clashes with glad, so it stays in a translation unit of its own).
#include <aquarelle/core/gl_context.h>

#include <algorithm>

#include <glad/gl.h>

#include "context_backends.h"

namespace aq {

namespace {
uint32_t next_generation() {
  static uint32_t generation = 0;
  return ++generation;
}
}  // namespace

const char* backend_name(GlBackend backend) {
  switch (backend) {
    case GlBackend::kAuto:
      return "auto";
    case GlBackend::kEgl:
      return "egl";
    case GlBackend::kOsmesa:
      return "osmesa";
    case GlBackend::kExternal:
      return "window";
  }
  return "?";
}

Result<GlBackend> parse_backend(const std::string& name) {
  if (name == "auto") return GlBackend::kAuto;
  if (name == "egl") return GlBackend::kEgl;
  if (name == "osmesa") return GlBackend::kOsmesa;
  return make_error("unknown GL backend '" + name + "': use auto, egl or osmesa");
}

std::string GlContext::description() const {
  auto text = [](GLenum name) {
    const GLubyte* s = glGetString(name);
    return s != nullptr ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  return "OpenGL " + text(GL_VERSION) + ", " + text(GL_RENDERER) + " (" + backend_name(backend()) +
         ")";
}

namespace {
uint64_t& last_loaded() {
  static uint64_t serial = 0;
  return serial;
}
uint64_t next_serial() {
  static uint64_t serial = 0;
  return ++serial;
}
}  // namespace

GlContext::GlContext() : serial_(next_serial()) {}

GlContext::~GlContext() {
  if (last_loaded() == serial_) last_loaded() = 0;
}

bool GlContext::activate() {
  if (!make_current()) return false;
  if (last_loaded() == serial_) return true;
  return load_functions();
}

bool GlContext::load_functions() {
  static const GlContext* loading = nullptr;
  loading = this;
  last_loaded() = serial_;
  int version = gladLoadGLUserPtr(
      [](void* self, const char* name) -> GLADapiproc {
        return reinterpret_cast<GLADapiproc>(
            static_cast<const GlContext*>(self)->get_proc_address(name));
      },
      const_cast<GlContext*>(loading));
  if (version == 0) return false;
  generation_ = next_generation();
  return GLAD_VERSION_MAJOR(version) > 4 ||
         (GLAD_VERSION_MAJOR(version) == 4 && GLAD_VERSION_MINOR(version) >= 5);
}

Status check_gl_device(const std::string& device) {
  const bool number =
      !device.empty() && device.size() <= 4 &&
      std::all_of(device.begin(), device.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (device == "auto" || device == "software" || number) return Ok{};
  return make_error("GL device '" + device +
                    "' must be auto, software or the index of an EGL device (0, 1, ...)");
}

Result<std::unique_ptr<GlContext>> create_headless_context(GlBackend backend,
                                                           const std::string& device) {
  if (backend == GlBackend::kEgl) return create_egl_context(device);
  if (backend == GlBackend::kOsmesa) return create_osmesa_context();
  if (backend == GlBackend::kExternal) {
    return make_error("an external (window) context cannot be created headless");
  }
  // A device names an EGL device: no quiet fallback to OSMesa when it cannot be had.
  if (!device.empty() && device != "auto") return create_egl_context(device);
  auto egl = create_egl_context(device);
  if (egl.ok()) return egl;
  auto osmesa = create_osmesa_context();
  if (osmesa.ok()) return osmesa;
  return make_error_lines("no OpenGL 4.5 core context could be created.\n  EGL: " + egl.message() +
                    "\n  OSMesa: " + osmesa.message() +
                    "\n  Install Mesa's EGL and OSMesa drivers (apt-get install libegl1 "
                    "libegl-mesa0 libosmesa6) or run on a machine with a GPU driver.");
}

namespace {
class ExternalContext final : public GlContext {
 public:
  explicit ExternalContext(void* (*proc)(const char*)) : proc_(proc) { load_functions(); }
  GlBackend backend() const override { return GlBackend::kExternal; }
  bool make_current() override { return true; }
  void* get_proc_address(const char* name) const override { return proc_(name); }

 private:
  void* (*proc_)(const char*);
};
}  // namespace

std::unique_ptr<GlContext> adopt_current_context(void* (*get_proc_address)(const char*)) {
  return std::make_unique<ExternalContext>(get_proc_address);
}

}  // namespace aq
