// Header-only C++ helper over the C ABI in plugin.h, so that a node reads like this:
//
//   constexpr aq_port_desc kIn[] = {aq::image_port("image", "colour to tint")};
//   constexpr aq_port_desc kOut[] = {aq::image_port("image", "tinted colour")};
//   constexpr aq_param_desc kParams[] = {aq::float_param("amount", 0.75, 0, 1, "mix factor")};
//   struct Tint {
//     int process(aq::Context& ctx) { ... bind inputs, one shader, ctx.draw(out) ... }
//   };
//   AQ_NODE(kTint, Tint, "tint", "Color", "Mixes towards a colour", AQ_NODE_POINTWISE,
//           kIn, kOut, kParams);
//   AQ_PLUGIN("tint", "1.0", &kTint)
//
// Everything here is inline and compiled into the plugin; only plugin.h types cross the
// boundary. GL calls go through glad, loaded from the host's get_proc_address and reloaded
// whenever the host says the context changed (ctx.gl_generation).
#pragma once

#include <glad/gl.h>

#include <aquarelle/plugin.h>
#include <aquarelle/sdk/region.hpp>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <new>
#include <optional>
#include <string>
#include <vector>

namespace aq {

// ---- Description helpers (constexpr, so tables stay static data) ----------------------

constexpr aq_port_desc image_port(const char* name, const char* description, uint32_t flags = 0) {
  return aq_port_desc{name, AQ_PORT_IMAGE, flags, description};
}
constexpr aq_port_desc optional_image_port(const char* name, const char* description) {
  return aq_port_desc{name, AQ_PORT_IMAGE, AQ_PORT_OPTIONAL, description};
}
constexpr aq_port_desc scene_port(const char* name, const char* description) {
  return aq_port_desc{name, AQ_PORT_SCENE, 0, description};
}
constexpr aq_port_desc optional_scene_port(const char* name, const char* description) {
  return aq_port_desc{name, AQ_PORT_SCENE, AQ_PORT_OPTIONAL, description};
}
// A scene input taking any number of links (0 or more; AQ_PORT_MULTI), read with
// Context::link_count and Context::input_scene(input, link).
constexpr aq_port_desc multi_scene_port(const char* name, const char* description) {
  return aq_port_desc{name, AQ_PORT_SCENE, AQ_PORT_OPTIONAL | AQ_PORT_MULTI, description};
}

// Mesh i's surface (uvs, base colour texture, cut-out), or NULL when the scene has none (an
// older producer, or an untextured mesh).
inline const aq_mesh_surface* scene_surface(const aq_scene& scene, uint32_t i) {
  const bool present = scene.struct_size >=
                       offsetof(aq_scene, surface_struct_size) + sizeof(scene.surface_struct_size);
  if (!present || scene.surfaces == nullptr || i >= scene.mesh_count ||
      scene.surface_struct_size < offsetof(aq_mesh_surface, art_set)) {
    return nullptr;
  }
  const char* base = reinterpret_cast<const char*>(scene.surfaces);
  return reinterpret_cast<const aq_mesh_surface*>(base + size_t{i} * scene.surface_struct_size);
}
// A copy of mesh i's surface with the fields its producer did not have zeroed (an older
// producer's stride is shorter than aq_mesh_surface: copy only what it wrote); zeroed when the
// scene has none.
inline aq_mesh_surface copy_surface(const aq_scene& scene, uint32_t i) {
  aq_mesh_surface copy{};
  if (const aq_mesh_surface* s = scene_surface(scene, i)) {
    std::memcpy(&copy, s, std::min<size_t>(scene.surface_struct_size, sizeof(aq_mesh_surface)));
  }
  return copy;
}

// Mesh i's art direction (seed 002): the producer's when its surface carries one, else the
// defaults plugin.h gives (bleed 0, edge darkening 1, no tremor, no FBM variation).
struct ArtDirection {
  float bleed = 0.0f, edge_darkening = 1.0f, tremor = 0.0f, tremor_frequency = 4.0f;
  float fbm_density = 0.0f, fbm_scale = 2.0f;
};
inline ArtDirection surface_art(const aq_scene& scene, uint32_t i) {
  ArtDirection art;
  const aq_mesh_surface* s = scene_surface(scene, i);
  if (s == nullptr || scene.surface_struct_size < sizeof(aq_mesh_surface) || s->art_set == 0) {
    return art;
  }
  art.bleed = s->bleed;
  art.edge_darkening = s->edge_darkening;
  art.tremor = s->tremor;
  art.tremor_frequency = s->tremor_frequency;
  art.fbm_density = s->fbm_density;
  art.fbm_scale = s->fbm_scale;
  return art;
}

// Whether the scene asks for an environment behind it (the gradient in environment_top/bottom).
inline bool scene_has_environment(const aq_scene& scene) {
  const bool present = scene.struct_size >=
                       offsetof(aq_scene, environment_bottom) + sizeof(scene.environment_bottom);
  return present && scene.has_environment != 0;
}

// The scene's caustic tile in world units; 4 (the period before the field existed) for a
// scene from an older plugin or with a value that is not a positive number.
inline double scene_caustic_tile(const aq_scene& scene) {
  const bool present = scene.struct_size >= offsetof(aq_scene, caustic_tile) + sizeof(float);
  return present && scene.caustic_tile > 0.0f && scene.caustic_tile < 1e30f
             ? static_cast<double>(scene.caustic_tile)
             : 4.0;
}

constexpr aq_param_desc float_param(const char* name, double def, double min, double max,
                                    const char* description, double step = 0.0,
                                    const char* ui_hint = "slider") {
  return aq_param_desc{name, AQ_PARAM_FLOAT, {def, 0, 0}, min,     max,
                       step, nullptr,        nullptr,     ui_hint, description};
}
constexpr aq_param_desc int_param(const char* name, int64_t def, int64_t min, int64_t max,
                                  const char* description) {
  return aq_param_desc{name,
                       AQ_PARAM_INT,
                       {static_cast<double>(def), 0, 0},
                       static_cast<double>(min),
                       static_cast<double>(max),
                       1.0,
                       nullptr,
                       nullptr,
                       "slider",
                       description};
}
constexpr aq_param_desc bool_param(const char* name, bool def, const char* description) {
  return aq_param_desc{
      name,       AQ_PARAM_BOOL, {def ? 1.0 : 0.0, 0, 0}, 0, 1, 1, nullptr, nullptr,
      "checkbox", description};
}
// `values` is "a|b|c"; `def` is the index of the default.
constexpr aq_param_desc enum_param(const char* name, const char* values, int def,
                                   const char* description) {
  return aq_param_desc{
      name,    AQ_PARAM_ENUM, {static_cast<double>(def), 0, 0}, 0, 0, 0, nullptr, values,
      "combo", description};
}
constexpr aq_param_desc color_param(const char* name, double r, double g, double b,
                                    const char* description) {
  return aq_param_desc{name, AQ_PARAM_COLOR, {r, g, b}, 0.0,     1.0,
                       0,    nullptr,        nullptr,   "color", description};
}
constexpr aq_param_desc vec3_param(const char* name, double x, double y, double z, double min,
                                   double max, const char* description) {
  return aq_param_desc{name, AQ_PARAM_VEC3, {x, y, z}, min,    max,
                       0,    nullptr,       nullptr,   "drag", description};
}
constexpr aq_param_desc string_param(const char* name, const char* def, const char* description) {
  return aq_param_desc{name, AQ_PARAM_STRING, {0, 0, 0}, 0,          0, 0,
                       def,  nullptr,         "text",    description};
}
constexpr aq_param_desc path_param(const char* name, const char* description) {
  return aq_param_desc{name, AQ_PARAM_PATH, {0, 0, 0}, 0, 0, 0, "", nullptr, "file", description};
}

// ---- GL loading ----------------------------------------------------------------------

inline const aq_host*& current_host() {
  static const aq_host* host = nullptr;
  return host;
}
inline void* load_gl_function(const char* name) {
  return current_host()->get_proc_address(name);
}
// Loads glad for this plugin when the host's context generation changed. Each plugin holds its
// own copy of glad (hidden symbols), so this is per plugin.
inline bool ensure_gl(const aq_process_ctx* ctx) {
  static uint32_t loaded_generation = 0;
  if (loaded_generation == ctx->gl_generation && loaded_generation != 0) return true;
  current_host() = ctx->host;
  if (gladLoadGL(reinterpret_cast<GLADloadfunc>(&load_gl_function)) == 0) return false;
  loaded_generation = ctx->gl_generation;
  return true;
}

// ---- Per-call context ----------------------------------------------------------------

class Context {
 public:
  explicit Context(aq_process_ctx* raw) : raw_(raw) {}

  aq_process_ctx* raw() const { return raw_; }
  const char* node_id() const { return raw_->node_id; }
  int width() const { return raw_->width; }
  int height() const { return raw_->height; }
  double time() const { return raw_->time; }
  int frame() const { return raw_->frame; }
  uint32_t working_format() const { return raw_->working_format; }
  bool precise() const { return raw_->precision == AQ_PRECISION_FLOAT; }
  uint32_t quality() const { return raw_->quality; }
  // Working pixels per output pixel; multiply parameters given in (output) pixels by it.
  double render_scale() const {
    const bool present =
        raw_->struct_size >= offsetof(aq_process_ctx, render_scale) + sizeof(double);
    return present && raw_->render_scale > 0.0 ? raw_->render_scale : 1.0;
  }

  bool connected(uint32_t input) const {
    return input < raw_->input_count && raw_->inputs[input].connected != 0;
  }
  aq_image input_image(uint32_t input) const {
    return connected(input) ? raw_->inputs[input].image : aq_image{0, 0, 0, 0};
  }
  const aq_scene* input_scene(uint32_t input) const {
    return connected(input) ? raw_->inputs[input].scene : nullptr;
  }
  // The host's key of what input `input` holds (aq_process_ctx::input_keys): equal keys on two
  // calls mean the same content. 0 when unconnected or unknown (an older host): assume nothing.
  uint64_t input_key(uint32_t input) const {
    return connected(input) && has_input_keys() ? raw_->input_keys[input] : 0;
  }
  // Links of an AQ_PORT_MULTI input (any input: 0 or 1 for a plain one), in graph order.
  uint32_t link_count(uint32_t input) const {
    if (input >= raw_->input_count) return 0;
    if (has_input_lists()) return raw_->input_lists[input].count;
    return connected(input) ? 1u : 0u;
  }
  const aq_scene* input_scene(uint32_t input, uint32_t link) const {
    if (link >= link_count(input)) return nullptr;
    if (!has_input_lists()) return input_scene(input);
    const aq_input_value& value = raw_->input_lists[input].values[link];
    return value.connected != 0 ? value.scene : nullptr;
  }
  // After output(index, ...): true when the texture holds what this instance left in output
  // `index` on an earlier call (aq_host::output_kept); false for a texture of unknown content
  // and from hosts that predate it.
  bool output_kept(uint32_t index) const {
    const aq_host* host = raw_->host;
    if (host->struct_size < offsetof(aq_host, output_kept) + sizeof(host->output_kept) ||
        host->output_kept == nullptr)
      return false;
    return host->output_kept(raw_->host_data, index) != 0;
  }
  // Damage tracking (aq_host::input_damage): where image input `input` may differ from what it
  // held on this instance's last call; everything from a host that predates it.
  Region input_damage(uint32_t input) const {
    if (!has_host_call(offsetof(aq_host, input_damage), raw_->host->input_damage != nullptr))
      return Region::everything();
    return damage_from([&](aq_rect* rects, uint32_t capacity) {
      return raw_->host->input_damage(raw_->host_data, input, rects, capacity);
    });
  }
  // With a fused epilogue: the pixels its other inputs or parameters changed (nothing without).
  Region epilogue_damage() const {
    if (!has_host_call(offsetof(aq_host, epilogue_damage), raw_->host->epilogue_damage != nullptr))
      return Region::everything();
    return damage_from([&](aq_rect* rects, uint32_t capacity) {
      return raw_->host->epilogue_damage(raw_->host_data, rects, capacity);
    });
  }
  // This call changed kept output `index` only in `region` (nothing is said for all()).
  bool set_output_damage(uint32_t index, const Region& region) const {
    if (region.all() || !has_host_call(offsetof(aq_host, set_output_damage),
                                       raw_->host->set_output_damage != nullptr))
      return true;
    const std::vector<aq_rect> rects = rects_of(region);
    return raw_->host->set_output_damage(raw_->host_data, index, rects.data(),
                                         static_cast<uint32_t>(rects.size())) == AQ_OK;
  }
  // Where image input `input` may hold anything but its background (aq_host::input_bounds);
  // everything when its writer did not say.
  Region input_bounds(uint32_t input) const {
    if (!has_host_call(offsetof(aq_host, input_bounds), raw_->host->input_bounds != nullptr))
      return Region::everything();
    return damage_from([&](aq_rect* rects, uint32_t capacity) {
      return raw_->host->input_bounds(raw_->host_data, input, rects, capacity);
    });
  }
  // Output `index` holds its background outside `region` (nothing is said for all()).
  bool set_output_bounds(uint32_t index, const Region& region) const {
    if (region.all() || !has_host_call(offsetof(aq_host, set_output_bounds),
                                       raw_->host->set_output_bounds != nullptr))
      return true;
    const std::vector<aq_rect> rects = rects_of(region);
    return raw_->host->set_output_bounds(raw_->host_data, index, rects.data(),
                                         static_cast<uint32_t>(rects.size())) == AQ_OK;
  }
  // Whether anything reads output `index` in this evaluation (true from an older host): an
  // unread output may be left unwritten.
  bool output_read(uint32_t index) const {
    return !has_host_call(offsetof(aq_host, output_read), raw_->host->output_read != nullptr) ||
           raw_->host->output_read(raw_->host_data, index) == 1;
  }
  // Neighbourhood fusion of separable filters (AQ_PORT_DEFER_AXIS): whether output `index` may
  // be left with its last 1D pass undone for its reader (false from an older host) ...
  bool may_defer_axis(uint32_t index) const {
    return has_host_call(offsetof(aq_host, may_defer_axis),
                         raw_->host->may_defer_axis != nullptr) &&
           raw_->host->may_defer_axis(raw_->host_data, index) == 1;
  }
  // ... this call left `pass` undone on output `index` (only where may_defer_axis said so) ...
  bool defer_axis(uint32_t index, const aq_axis_pass& pass) const {
    return has_host_call(offsetof(aq_host, defer_axis), raw_->host->defer_axis != nullptr) &&
           raw_->host->defer_axis(raw_->host_data, index, &pass) == AQ_OK;
  }
  // ... and the pass image input `input` still needs, if its writer left one.
  std::optional<aq_axis_pass> input_deferred_axis(uint32_t input) const {
    aq_axis_pass pass{};
    if (!has_host_call(offsetof(aq_host, input_deferred_axis),
                       raw_->host->input_deferred_axis != nullptr) ||
        raw_->host->input_deferred_axis(raw_->host_data, input, &pass) != 1)
      return std::nullopt;
    return pass;
  }
  // draw() and draw_fullscreen cover only `region` until the next call (all(): everything).
  // False from a host that predates it: then draw everything and declare no damage.
  bool set_draw_region(const Region& region) const {
    if (!has_host_call(offsetof(aq_host, set_draw_region), raw_->host->set_draw_region != nullptr))
      return region.all();
    if (region.all()) {
      raw_->host->set_draw_region(raw_->host_data, nullptr, 0);
    } else {
      std::vector<aq_rect> rects = rects_of(region);
      aq_rect none{};  // an empty region still passes rects: NULL would mean everything
      raw_->host->set_draw_region(raw_->host_data, rects.empty() ? &none : rects.data(),
                                  static_cast<uint32_t>(rects.size()));
    }
    return true;
  }
  // Reads an image file through the host (OIIO + OCIO, working space, straight alpha, row 0 at
  // the bottom) into `rgba`; false with `error` set when it cannot (or the host is too old).
  bool read_image(const std::string& path, std::vector<float>* rgba, int* width, int* height,
                  std::string* error) const {
    const aq_host* host = raw_->host;
    if (host->struct_size < offsetof(aq_host, read_image) + sizeof(host->read_image) ||
        host->read_image == nullptr) {
      *error = "this host cannot read images for plugins (it predates aq_host::read_image)";
      return false;
    }
    struct Sink {
      std::vector<float>* rgba;
      int* width;
      int* height;
    } sink{rgba, width, height};
    auto receive = [](void* user, const float* pixels, int32_t w, int32_t h) {
      auto* s = static_cast<Sink*>(user);
      s->rgba->assign(pixels, pixels + static_cast<size_t>(w) * static_cast<size_t>(h) * 4);
      *s->width = w;
      *s->height = h;
    };
    char message[1024] = {0};
    if (host->read_image(raw_->host_data, path.c_str(), receive, &sink, message, sizeof(message)) !=
        AQ_OK) {
      *error = message;
      return false;
    }
    return true;
  }

  double param_float(uint32_t p) const { return raw_->params[p].f[0]; }
  int64_t param_int(uint32_t p) const { return raw_->params[p].i; }
  bool param_bool(uint32_t p) const { return raw_->params[p].i != 0; }
  int64_t param_enum(uint32_t p) const { return raw_->params[p].i; }
  const double* param_vec3(uint32_t p) const { return raw_->params[p].f; }
  const char* param_string(uint32_t p) const {
    return raw_->params[p].s != nullptr ? raw_->params[p].s : "";
  }

  // Records an error; always returns AQ_ERROR so `return ctx.fail(...)` reads naturally.
  int fail(const std::string& message) const {
    raw_->host->fail(raw_->host_data, message.c_str());
    return AQ_ERROR;
  }
  void warn(const std::string& message) const {
    raw_->host->log(raw_->host_data, 1, message.c_str());
  }

  GLuint program(const aq_shader_source& fragment) const {
    return raw_->host->program(raw_->host_data, nullptr, &fragment);
  }
  GLuint program(const aq_shader_source& vertex, const aq_shader_source& fragment) const {
    return raw_->host->program(raw_->host_data, &vertex, &fragment);
  }

  bool output(uint32_t index, int w, int h, uint32_t format, aq_image* out) const {
    return raw_->host->output_image(raw_->host_data, index, w, h, format, out) == AQ_OK;
  }
  // An output the size of `like`, in the working format.
  bool output_like(uint32_t index, const aq_image& like, aq_image* out) const {
    return output(index, like.width, like.height, raw_->working_format, out);
  }
  bool pass_through(uint32_t index, uint32_t input) const {
    return raw_->host->pass_through(raw_->host_data, index, input) == AQ_OK;
  }
  bool output_scene(uint32_t index, const aq_scene* scene) const {
    return raw_->host->output_scene(raw_->host_data, index, scene) == AQ_OK;
  }
  bool scratch(int w, int h, uint32_t format, aq_image* out) const {
    return raw_->host->scratch_image(raw_->host_data, w, h, format, out) == AQ_OK;
  }
  bool bind_targets(const aq_image* colors, uint32_t count, const aq_image* depth = nullptr) const {
    return raw_->host->bind_targets(raw_->host_data, colors, count, depth) == AQ_OK;
  }
  // Draws the bound program as a full-screen triangle into `target`.
  bool draw(const aq_image& target) const {
    if (!bind_targets(&target, 1, nullptr)) return false;
    raw_->host->draw_fullscreen(raw_->host_data);
    return true;
  }

 private:
  bool has_host_call(size_t offset, bool set) const {
    return raw_->host->struct_size >= offset + sizeof(void*) && set;
  }
  template <typename Query>
  static Region damage_from(Query query) {
    std::vector<aq_rect> rects(Region::kMaxRects);
    const int count = query(rects.data(), static_cast<uint32_t>(rects.size()));
    if (count < 0) return Region::everything();
    return region_of(rects.data(), static_cast<size_t>(count));
  }
  bool has_input_keys() const {
    return raw_->struct_size >= offsetof(aq_process_ctx, input_keys) + sizeof(void*) &&
           raw_->input_keys != nullptr;
  }
  bool has_input_lists() const {
    return raw_->struct_size >= offsetof(aq_process_ctx, input_lists) + sizeof(void*) &&
           raw_->input_lists != nullptr;
  }
  aq_process_ctx* raw_;
};

// ---- Uniform helpers (bound program) ---------------------------------------------------

inline void bind_texture(GLuint program, const char* name, GLuint unit, const aq_image& image) {
  glActiveTexture(GL_TEXTURE0 + unit);
  glBindTexture(GL_TEXTURE_2D, image.texture);
  glUniform1i(glGetUniformLocation(program, name), static_cast<GLint>(unit));
}
inline void set_float(GLuint program, const char* name, double v) {
  glUniform1f(glGetUniformLocation(program, name), static_cast<float>(v));
}
inline void set_int(GLuint program, const char* name, int v) {
  glUniform1i(glGetUniformLocation(program, name), v);
}
inline void set_vec2(GLuint program, const char* name, double x, double y) {
  glUniform2f(glGetUniformLocation(program, name), static_cast<float>(x), static_cast<float>(y));
}
inline void set_vec3(GLuint program, const char* name, const double* v) {
  glUniform3f(glGetUniformLocation(program, name), static_cast<float>(v[0]),
              static_cast<float>(v[1]), static_cast<float>(v[2]));
}
inline void set_vec3(GLuint program, const char* name, const float* v) {
  glUniform3f(glGetUniformLocation(program, name), v[0], v[1], v[2]);
}
inline void set_mat4(GLuint program, const char* name, const float* m) {
  glUniformMatrix4fv(glGetUniformLocation(program, name), 1, GL_FALSE, m);
}
// Unbinds what a node typically binds, so no GL state leaks into the next node.
inline void unbind_textures(GLuint units) {
  for (GLuint u = 0; u < units; ++u) {
    glActiveTexture(GL_TEXTURE0 + u);
    glBindTexture(GL_TEXTURE_2D, 0);
  }
  glActiveTexture(GL_TEXTURE0);
  glUseProgram(0);
}

// ---- Adapting a C++ node class to the C function table -------------------------------

template <typename NodeClass>
struct NodeAdapter {
  static void* create(const aq_host* host) {
    current_host() = host;
    return new (std::nothrow) NodeClass();
  }
  static void destroy(void* instance) { delete static_cast<NodeClass*>(instance); }
  static int process(void* instance, aq_process_ctx* raw) {
    Context ctx(raw);
    if (!ensure_gl(raw)) return ctx.fail("could not load OpenGL functions from the host");
    try {
      return static_cast<NodeClass*>(instance)->process(ctx);
    } catch (const std::exception& e) {
      return ctx.fail(std::string("internal error: ") + e.what());
    } catch (...) {
      return ctx.fail("internal error (unknown exception)");
    }
  }
};

// The fusion hook of a pointwise node (aq_pointwise_desc::set_uniforms): NodeClass has
// `int set_uniforms(aq::Context& ctx, GLuint program, const std::string& prefix)`.
template <typename NodeClass>
struct PointwiseAdapter {
  static int set_uniforms(void* instance, aq_process_ctx* raw, uint32_t program,
                          const char* prefix) {
    Context ctx(raw);
    if (!ensure_gl(raw)) return ctx.fail("could not load OpenGL functions from the host");
    try {
      return static_cast<NodeClass*>(instance)->set_uniforms(ctx, program,
                                                             prefix != nullptr ? prefix : "");
    } catch (const std::exception& e) {
      return ctx.fail(std::string("internal error: ") + e.what());
    } catch (...) {
      return ctx.fail("internal error (unknown exception)");
    }
  }
};

// The stand-alone fragment shader of a pointwise node from its fusable function (see
// aq_pointwise_desc): reads the input texel, applies the function, writes the result. A
// node's process() uses it so that its own pass and the host's fused pass share one
// definition.
// encode_hdr8: the output is stored as AQ_FORMAT_RGBA8_HDR (aquarelle/hdr8.glsl encodes it).
inline std::string pointwise_fragment(const char* glsl, bool encode_hdr8 = false) {
  return std::string(encode_hdr8 ? "#include \"aquarelle/hdr8.glsl\"\n" : "") +
         "#define AQ_APPLY aq_apply\n#define AQ_UNIFORM(name) u_##name\n" + glsl +
         "\nlayout(location = 0) out vec4 o_color;\n"
         "uniform sampler2D u_image;\n"
         "void main() {\n"
         "  vec4 c = texelFetch(u_image, ivec2(gl_FragCoord.xy), 0);\n"
         "  o_color = aq_apply(c, gl_FragCoord.xy, vec2(textureSize(u_image, 0)));\n" +
         (encode_hdr8 ? "  o_color = aq_hdr8_encode(o_color);\n" : "") + "}\n";
}

template <typename T, size_t N>
constexpr uint32_t count_of(const T (&)[N]) {
  return static_cast<uint32_t>(N);
}

}  // namespace aq

// Defines `const aq_node_desc NAME` for NodeClass. Inputs, outputs and params are arrays.
#define AQ_NODE(NAME, NodeClass, type_name, category, description, flags, inputs, outputs, params) \
  static const aq_node_desc NAME = {sizeof(aq_node_desc),                                          \
                                    type_name,                                                     \
                                    category,                                                      \
                                    description,                                                   \
                                    flags,                                                         \
                                    inputs,                                                        \
                                    aq::count_of(inputs),                                          \
                                    outputs,                                                       \
                                    aq::count_of(outputs),                                         \
                                    params,                                                        \
                                    aq::count_of(params),                                          \
                                    &aq::NodeAdapter<NodeClass>::create,                           \
                                    &aq::NodeAdapter<NodeClass>::destroy,                          \
                                    &aq::NodeAdapter<NodeClass>::process,                          \
                                    nullptr,                                                       \
                                    nullptr}

// Same, for a pointwise node the host may fuse: `glsl` is the aq_shader_source of its
// per-pixel function (see aq_pointwise_desc), `reach` how far from the pixel it reads its other
// inputs (-1: anywhere) and NodeClass has set_uniforms (PointwiseAdapter).
#define AQ_POINTWISE_NODE(NAME, NodeClass, type_name, category, description, inputs, outputs, \
                          params, glsl, reach)                                                \
  static const aq_pointwise_desc NAME##_pointwise = {                                         \
      sizeof(aq_pointwise_desc), (glsl).name, (glsl).text,                                    \
      &aq::PointwiseAdapter<NodeClass>::set_uniforms, (reach)};                               \
  static const aq_node_desc NAME = {sizeof(aq_node_desc),                                     \
                                    type_name,                                                \
                                    category,                                                 \
                                    description,                                              \
                                    AQ_NODE_POINTWISE,                                        \
                                    inputs,                                                   \
                                    aq::count_of(inputs),                                     \
                                    outputs,                                                  \
                                    aq::count_of(outputs),                                    \
                                    params,                                                   \
                                    aq::count_of(params),                                     \
                                    &aq::NodeAdapter<NodeClass>::create,                      \
                                    &aq::NodeAdapter<NodeClass>::destroy,                     \
                                    &aq::NodeAdapter<NodeClass>::process,                     \
                                    &NAME##_pointwise,                                        \
                                    nullptr}

// Same as AQ_NODE, for a node without parameters.
#define AQ_NODE_NO_PARAMS(NAME, NodeClass, type_name, category, description, flags, inputs, \
                          outputs)                                                          \
  static const aq_node_desc NAME = {sizeof(aq_node_desc),                                   \
                                    type_name,                                              \
                                    category,                                               \
                                    description,                                            \
                                    flags,                                                  \
                                    inputs,                                                 \
                                    aq::count_of(inputs),                                   \
                                    outputs,                                                \
                                    aq::count_of(outputs),                                  \
                                    nullptr,                                                \
                                    0,                                                      \
                                    &aq::NodeAdapter<NodeClass>::create,                    \
                                    &aq::NodeAdapter<NodeClass>::destroy,                   \
                                    &aq::NodeAdapter<NodeClass>::process,                   \
                                    nullptr,                                                \
                                    nullptr}

// Same, for a source node: no inputs (generators such as noise, caustics, scene).
#define AQ_SOURCE_NODE(NAME, NodeClass, type_name, category, description, flags, outputs, params) \
  AQ_SOURCE_NODE_CHECKED(NAME, NodeClass, type_name, category, description, flags, outputs,       \
                         params, nullptr)

// Same as AQ_SOURCE_NODE with a validate-time file check (aq_node_desc::check).
#define AQ_SOURCE_NODE_CHECKED(NAME, NodeClass, type_name, category, description, flags, outputs, \
                               params, check_function)                                            \
  static const aq_node_desc NAME = {sizeof(aq_node_desc),                                         \
                                    type_name,                                                    \
                                    category,                                                     \
                                    description,                                                  \
                                    flags,                                                        \
                                    nullptr,                                                      \
                                    0,                                                            \
                                    outputs,                                                      \
                                    aq::count_of(outputs),                                        \
                                    params,                                                       \
                                    aq::count_of(params),                                         \
                                    &aq::NodeAdapter<NodeClass>::create,                          \
                                    &aq::NodeAdapter<NodeClass>::destroy,                         \
                                    &aq::NodeAdapter<NodeClass>::process,                         \
                                    nullptr,                                                      \
                                    check_function}

// Exports the plugin entry point listing the given node descriptions (pointers).
#define AQ_PLUGIN(plugin_name, plugin_version, ...)                                    \
  extern "C" AQ_PLUGIN_EXPORT const aq_plugin_desc* aquarelle_plugin_entry(uint32_t) { \
    static const aq_node_desc* const nodes[] = {__VA_ARGS__};                          \
    static const aq_plugin_desc desc = {AQ_ABI_VERSION, sizeof(aq_plugin_desc),        \
                                        plugin_name,    plugin_version,                \
                                        nodes,          aq::count_of(nodes)};          \
    return &desc;                                                                      \
  }
