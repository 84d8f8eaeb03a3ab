// Constructors of the headless backends, each in its own translation unit (see gl_context.cpp).
#pragma once

#include <aquarelle/core/gl_context.h>

namespace aq {

// `device`: "auto" (a hardware EGL device, else Mesa's surfaceless platform), "software" (the
// surfaceless platform) or the index of an EGL device.
Result<std::unique_ptr<GlContext>> create_egl_context(const std::string& device);
Result<std::unique_ptr<GlContext>> create_osmesa_context();

// Lets a backend subclass call the protected loader.
class BackendContext : public GlContext {
 protected:
  bool load() { return load_functions(); }
};

}  // namespace aq
