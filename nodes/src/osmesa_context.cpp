// Headless OSMesa context (the fallback: OSMesa is gone from recent Mesa upstream). Its header
// pulls <GL/gl.h>, so this file must not include glad; GL functions are reached only through
// OSMesaGetProcAddress and the core's glad.
#include <GL/osmesa.h>

#include <vector>

#include "context_backends.h"

namespace aq {

namespace {

class OsmesaContext final : public BackendContext {
 public:
  ~OsmesaContext() override {
    if (context_ != nullptr) OSMesaDestroyContext(context_);
  }
  GlBackend backend() const override { return GlBackend::kOsmesa; }
  bool make_current() override {
    // OSMesa needs a colour buffer even though every pass renders into FBOs; keep it tiny.
    return OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1) != 0;
  }
  void* get_proc_address(const char* name) const override {
    return reinterpret_cast<void*>(OSMesaGetProcAddress(name));
  }

  Status init() {
    const int attributes[] = {OSMESA_FORMAT,        OSMESA_RGBA,        OSMESA_DEPTH_BITS, 0,
                              OSMESA_PROFILE,       OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION,
                              4,                    OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
    context_ = OSMesaCreateContextAttribs(attributes, nullptr);
    if (context_ == nullptr) return make_error("OSMesa refused an OpenGL 4.5 core context");
    buffer_.assign(4, 0);
    if (!make_current()) return make_error("OSMesaMakeCurrent failed");
    if (!load()) return make_error("the OSMesa context does not provide OpenGL 4.5 functions");
    return Ok{};
  }

 private:
  OSMesaContext context_ = nullptr;
  std::vector<unsigned char> buffer_;
};

}  // namespace

Result<std::unique_ptr<GlContext>> create_osmesa_context() {
  auto context = std::make_unique<OsmesaContext>();
  if (auto status = context->init(); !status.ok()) return status.error();
  return std::unique_ptr<GlContext>(std::move(context));
}

}  // namespace aq
