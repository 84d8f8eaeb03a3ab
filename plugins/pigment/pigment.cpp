// pigment: pigment density variation (Bousseau et al. 2006, seed §3.6). Darkens and lightens
// the colour by three density textures in turn — turbulence, grain (pigment dispersion) and
// paper — each an optional input image or procedural. Anchoring: `screen` puts the textures on
// a dynamic canvas that follows the camera of the optional `scene` input; `object` evaluates
// the procedural turbulence and grain at the world position of the optional `position` input.
//
//   image ───────────────────────────────┐
//   [turbulence] [grain] [paper] ────────┤
//   [position] (object) ─────────────────┼──► pigment.frag ──► image
//   [scene] camera ─► pan, zoom (screen) ┘
#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/gl_raii.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "pigment_shaders.h"
#include "pigment_shared.h"

namespace {

constexpr aq_port_desc kInputs[] = {
    aq::image_port("image", "colour to modulate"),
    pigment::kDensityPorts[0],
    pigment::kDensityPorts[1],
    pigment::kDensityPorts[2],
    aq::optional_image_port("position",
                            "world position (gbuffer), w = 0 on the background; "
                            "used by object anchoring"),
    aq_port_desc{"scene", AQ_PORT_SCENE, AQ_PORT_OPTIONAL,
                 "its camera drives the dynamic canvas of screen anchoring"}};
// AQ_PORT_HDR8: written encoded (aquarelle/hdr8.glsl) when every reader decodes it (blur).
constexpr aq_port_desc kOutputs[] = {
    aq::image_port("image", "colour with pigment density", AQ_PORT_HDR8)};
enum Input : uint32_t { kImage, kTurbulence, kGrain, kPaper, kPosition, kScene };
enum Param : uint32_t {
  kAnchoring,
  kTurbulenceWeight,
  kTurbulenceFrequency,
  kGrainWeight,
  kGrainFrequency,
  kPaperWeight,
  kPaperFrequency,
  kWorldScale,
  kSeed,
  kCacheCanvas
};
constexpr aq_param_desc kParams[] = {
    aq::enum_param("anchoring", "screen|object", 0,
                   "screen: a dynamic canvas following the camera; object: turbulence and grain "
                   "fixed on the geometry (needs `position`)"),
    pigment::kWeightParams[0],
    aq::float_param("turbulence_frequency", 3.0, 0.01, 1000.0,
                    "procedural turbulence cells per image height (object: per world_scale)"),
    pigment::kWeightParams[1],
    aq::float_param("grain_frequency", 360.0, 0.01, 10000.0,
                    "procedural dispersion cells per image height (object: per world_scale)"),
    pigment::kWeightParams[2],
    aq::float_param("paper_frequency", 100.0, 0.01, 10000.0,
                    "procedural paper cells per image height (always on the canvas)"),
    aq::float_param("world_scale", 1.0, 0.001, 1e6, "object anchoring: world units per unit", 0.0,
                    "log"),
    pigment::kSeedParam,
    aq::bool_param("cache_canvas", true,
                   "screen anchoring: keep the procedural densities of the view in a texture "
                   "while the camera stays (same image, the noise computed once); off: computed "
                   "every frame")};

using pigment::Canvas;
using pigment::canvas_for;

// The procedural canvas densities of one view (pass 1 of pigment.frag), kept while the view,
// the size and the parameters they depend on stay the same.
struct CanvasCache {
  aq::gl::Texture texture;
  uint32_t generation = 0;
  std::string key;
};

struct Pigment {
  CanvasCache cache;

  int process(aq::Context& ctx) {
    const aq_image in = ctx.input_image(kImage);
    const std::array<float, 3> weights = {static_cast<float>(ctx.param_float(kTurbulenceWeight)),
                                          static_cast<float>(ctx.param_float(kGrainWeight)),
                                          static_cast<float>(ctx.param_float(kPaperWeight))};
    if (weights[0] == 0.0f && weights[1] == 0.0f && weights[2] == 0.0f) {
      return ctx.pass_through(0, kImage) ? AQ_OK : AQ_ERROR;
    }
    const bool object = ctx.param_enum(kAnchoring) == 1;
    if (object && !ctx.connected(kPosition)) {
      return ctx.fail(
          "anchoring 'object' needs the world position: connect the gbuffer's "
          "`position` output to the `position` input, or use anchoring 'screen'");
    }
    aq_image out;
    if (!ctx.output_like(0, in, &out)) return AQ_ERROR;
    const Canvas canvas = canvas_for(ctx.input_scene(kScene));
    // The variant holds only what this call uses (llvmpipe runs both sides of every branch).
    std::array<int, 3> modes{};
    for (uint32_t i = 0; i < 3; ++i)
      modes[i] = weights[i] == 0.0f ? 0 : (ctx.connected(kTurbulence + i) ? 1 : 2);
    std::string defines = pigment::canvas_defines(modes, canvas);
    defines += std::string("#define AQ_PIGMENT_OBJECT ") + (object ? "1" : "0") + "\n";
    // Screen anchoring with a procedural density: its values depend on the view alone.
    bool procedural = false;
    for (uint32_t i = 0; i < 3; ++i)
      procedural = procedural || (weights[i] != 0.0f && !ctx.connected(kTurbulence + i));
    const bool cached = !object && procedural && ctx.param_bool(kCacheCanvas);
    if (cached && !update_canvas_cache(ctx, in, defines, canvas)) return AQ_ERROR;
    const std::string text =
        defines + (cached ? "#define AQ_PIGMENT_PASS 2\n" : "#define AQ_PIGMENT_PASS 0\n") +
        "#define AQ_PIGMENT_ENCODE_HDR8 " + (out.format == AQ_FORMAT_RGBA8_HDR ? "1" : "0") + "\n" +
        shaders::pigment_frag.text;
    const GLuint program =
        ctx.program(aq_shader_source{shaders::pigment_frag.name, text.c_str(), nullptr});
    if (program == 0) return AQ_ERROR;
    glUseProgram(program);
    set_canvas_uniforms(ctx, program, in, canvas);
    if (cached)
      aq::bind_texture(program, "u_density", 5,
                       aq_image{cache.texture.get(), in.width, in.height, AQ_FORMAT_RGBA32F});

    // Unit 0: image; 1-3: the density textures (the image stands in for unconnected ones so
    // every sampler names a complete texture); 4: position.
    aq::bind_texture(program, "u_image", 0, in);
    pigment::bind_density_textures(ctx, program, kTurbulence, in.texture);
    aq::bind_texture(program, "u_position", 4, object ? ctx.input_image(kPosition) : in);
    glUniform1fv(glGetUniformLocation(program, "u_weights"), 3, weights.data());
    const bool drawn = ctx.draw(out);
    aq::unbind_textures(6);
    return drawn ? AQ_OK : AQ_ERROR;
  }

  // What the procedural densities depend on: frequencies, seed, aspect, the canvas view.
  static void set_canvas_uniforms(aq::Context& ctx, GLuint program, const aq_image& in,
                                  const Canvas& canvas) {
    pigment::DensityParams params;
    params.frequencies = {static_cast<float>(ctx.param_float(kTurbulenceFrequency)),
                          static_cast<float>(ctx.param_float(kGrainFrequency)),
                          static_cast<float>(ctx.param_float(kPaperFrequency))};
    params.world_scale = ctx.param_float(kWorldScale);
    params.seed = ctx.param_int(kSeed);
    pigment::set_canvas_uniforms(program, params, static_cast<double>(in.width) / in.height,
                                 canvas);
  }

  // Renders the densities of this view (pass 1) unless the cache already holds them.
  bool update_canvas_cache(aq::Context& ctx, const aq_image& in, const std::string& defines,
                           const Canvas& canvas) {
    char view[256];
    std::snprintf(view, sizeof(view), "%dx%d %a %a %a %a %a %a %lld|", in.width, in.height,
                  canvas.pan_x, canvas.pan_y, canvas.zoom, ctx.param_float(kTurbulenceFrequency),
                  ctx.param_float(kGrainFrequency), ctx.param_float(kPaperFrequency),
                  static_cast<long long>(ctx.param_int(kSeed)));
    const std::string key = view + defines;
    const uint32_t generation = ctx.raw()->gl_generation;
    if (cache.texture && cache.generation == generation && cache.key == key) return true;
    if (cache.generation != generation) cache.texture.forget();  // the old context's name
    cache.texture.create();
    glTextureStorage2D(cache.texture.get(), 1, GL_RGBA32F, in.width, in.height);
    cache.generation = generation;
    cache.key.clear();
    const std::string text = defines + "#define AQ_PIGMENT_PASS 1\n" + shaders::pigment_frag.text;
    const GLuint program =
        ctx.program(aq_shader_source{shaders::pigment_frag.name, text.c_str(), nullptr});
    if (program == 0) return false;
    glUseProgram(program);
    set_canvas_uniforms(ctx, program, in, canvas);
    // Every sampler names a complete texture, as in the main pass.
    pigment::bind_density_textures(ctx, program, kTurbulence, in.texture);
    aq::bind_texture(program, "u_image", 0, in);
    aq::bind_texture(program, "u_position", 4, in);
    if (!ctx.draw(aq_image{cache.texture.get(), in.width, in.height, AQ_FORMAT_RGBA32F}))
      return false;
    cache.key = key;
    return true;
  }
};

}  // namespace

AQ_NODE(kPigmentNode, Pigment, "pigment", "Watercolor",
        "Pigment density variation (Bousseau 2006): turbulence, pigment dispersion and paper "
        "grain modulate C' = C(1 − (1 − C)(d − 1)); screen (dynamic canvas) or object anchoring.",
        0, kInputs, kOutputs, kParams);
const aq_node_desc* pigment_canvas_node_desc();
const aq_node_desc* pigment_apply_node_desc();

AQ_PLUGIN("pigment", "1.0", &kPigmentNode, pigment_canvas_node_desc(), pigment_apply_node_desc())
