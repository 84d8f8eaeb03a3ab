// pigment_canvas: the pigment densities of the view (Bousseau et al. 2006, seed 000 §3.6) on
// the dynamic canvas of `pigment`'s screen anchoring — the per-view half of `pigment`, as an
// image `pigment_apply` reads at the pixel. Procedural turbulence (fBm), dispersion (Gaussian
// noise) and paper (Worley), or the connected images sampled on the canvas.
//
//   [turbulence] [grain] [paper] ──┐
//   [scene] camera ─► pan, zoom ───┴──► pigment.frag pass 1 ──► density (n + 0.5 in r, g, b)
//
// The densities depend on the view, the size, the parameters and the connected images only: the
// node keeps them while those stay (the images by the host's input keys) and copies them into
// its output each frame instead of computing the noise again — or does nothing when the host
// hands it back the output it filled last time, untouched (aq_host::output_kept).
#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/gl_raii.hpp>

#include <array>
#include <cstdio>
#include <string>

#include "canvas_view.h"
#include "pigment_shaders.h"

namespace {

constexpr aq_port_desc kInputs[] = {
    pigment::kDensityPorts[0], pigment::kDensityPorts[1], pigment::kDensityPorts[2],
    aq_port_desc{"scene", AQ_PORT_SCENE, AQ_PORT_OPTIONAL,
                 "its camera drives the dynamic canvas; unconnected: a still screen canvas"}};
constexpr aq_port_desc kOutputs[] = {aq::image_port(
    "density", "r turbulence, g grain, b paper: each density n + 0.5 (0.5 = none); a = 1")};
enum Input : uint32_t { kTurbulence, kGrain, kPaper, kScene };
enum Param : uint32_t { kTurbulenceFrequency, kGrainFrequency, kPaperFrequency, kSeed, kCache };
constexpr aq_param_desc kParams[] = {
    aq::float_param("turbulence_frequency", 3.0, 0.01, 1000.0,
                    "procedural turbulence cells per image height"),
    aq::float_param("grain_frequency", 360.0, 0.01, 10000.0,
                    "procedural dispersion cells per image height"),
    aq::float_param("paper_frequency", 100.0, 0.01, 10000.0,
                    "procedural paper cells per image height"),
    aq::int_param("seed", 0, 0, 1 << 20, "independent procedural textures per seed"),
    aq::bool_param("cache", true,
                   "keep the densities while the view, size, parameters and connected images "
                   "stay (the same image; off: computed every frame)")};

struct PigmentCanvas {
  int process(aq::Context& ctx) {
    const int width = ctx.width(), height = ctx.height();
    aq_image out;
    if (!ctx.output(0, width, height, ctx.working_format(), &out)) return AQ_ERROR;
    const pigment::Canvas canvas = pigment::canvas_for(ctx.input_scene(kScene));
    std::array<int, 3> modes{};
    for (uint32_t i = 0; i < 3; ++i) modes[i] = ctx.connected(kTurbulence + i) ? 1 : 2;
    const std::string defines = pigment::canvas_defines(modes, canvas) +
                                "#define AQ_PIGMENT_OBJECT 0\n#define AQ_PIGMENT_PASS 1\n"
                                "#define AQ_PIGMENT_BAKE_INPUTS 1\n"
                                "#define AQ_PIGMENT_DENSITY_OFFSET 0.5\n";
    pigment::DensityParams params;
    params.frequencies = {static_cast<float>(ctx.param_float(kTurbulenceFrequency)),
                          static_cast<float>(ctx.param_float(kGrainFrequency)),
                          static_cast<float>(ctx.param_float(kPaperFrequency))};
    params.seed = ctx.param_int(kSeed);

    std::string key = cache_key(ctx, out, canvas, params, defines);
    // The host handed back the very texture this call's densities went into last time.
    if (!key.empty() && ctx.output_kept(0) && drawn_key_ == key) return AQ_OK;
    drawn_key_.clear();
    if (!key.empty() && cache_.texture && cache_.generation == ctx.raw()->gl_generation &&
        cache_.key == key) {
      glCopyImageSubData(cache_.texture.get(), GL_TEXTURE_2D, 0, 0, 0, 0, out.texture,
                         GL_TEXTURE_2D, 0, 0, 0, 0, width, height, 1);
      drawn_key_ = key;
      return AQ_OK;
    }

    const std::string text = defines + shaders::pigment_frag.text;
    const GLuint program =
        ctx.program(aq_shader_source{shaders::pigment_frag.name, text.c_str(), nullptr});
    if (program == 0) return AQ_ERROR;
    aq_image stand_in;  // names a complete texture for the samplers pass 1 does not read
    if (!ctx.scratch(1, 1, AQ_FORMAT_RGBA8, &stand_in)) return AQ_ERROR;
    glUseProgram(program);
    pigment::set_canvas_uniforms(program, params, static_cast<double>(width) / height, canvas);
    pigment::bind_density_textures(ctx, program, kTurbulence, stand_in.texture);
    aq::bind_texture(program, "u_image", 0, stand_in);
    aq::bind_texture(program, "u_position", 4, stand_in);
    const bool drawn = ctx.draw(out);
    aq::unbind_textures(5);
    if (!drawn) return AQ_ERROR;
    if (!key.empty()) keep(ctx, out, key);
    drawn_key_ = key;
    return AQ_OK;
  }

 private:
  // Everything the densities depend on; empty when they cannot be kept (cache off, or a
  // connected image whose content the host does not identify).
  static std::string cache_key(aq::Context& ctx, const aq_image& out, const pigment::Canvas& canvas,
                               const pigment::DensityParams& params, const std::string& defines) {
    if (!ctx.param_bool(kCache)) return {};
    char view[320];
    std::snprintf(view, sizeof(view), "%dx%d f%u %a %a %a %a %a %a %lld|", out.width, out.height,
                  out.format, canvas.pan_x, canvas.pan_y, canvas.zoom,
                  static_cast<double>(params.frequencies[0]),
                  static_cast<double>(params.frequencies[1]),
                  static_cast<double>(params.frequencies[2]), static_cast<long long>(params.seed));
    std::string key = view + defines;
    for (uint32_t i = 0; i < 3; ++i) {
      if (!ctx.connected(kTurbulence + i)) continue;
      const uint64_t input = ctx.input_key(kTurbulence + i);
      if (input == 0) return {};
      key += std::to_string(i) + ":" + std::to_string(input) + "|";
    }
    return key;
  }

  // Copies the output into the kept texture (same GL format, so the copy is exact).
  void keep(aq::Context& ctx, const aq_image& out, const std::string& key) {
    GLint internal_format = 0;
    glGetTextureLevelParameteriv(out.texture, 0, GL_TEXTURE_INTERNAL_FORMAT, &internal_format);
    const uint32_t generation = ctx.raw()->gl_generation;
    if (cache_.generation != generation) cache_.texture.forget();  // the old context's name
    if (!cache_.texture || cache_.width != out.width || cache_.height != out.height ||
        cache_.internal_format != internal_format) {
      glTextureStorage2D(cache_.texture.create(), 1, static_cast<GLenum>(internal_format),
                         out.width, out.height);
      cache_.width = out.width;
      cache_.height = out.height;
      cache_.internal_format = internal_format;
    }
    glCopyImageSubData(out.texture, GL_TEXTURE_2D, 0, 0, 0, 0, cache_.texture.get(), GL_TEXTURE_2D,
                       0, 0, 0, 0, out.width, out.height, 1);
    cache_.generation = generation;
    cache_.key = key;
  }

  struct Kept {
    aq::gl::Texture texture;
    uint32_t generation = 0;
    int width = 0, height = 0;
    GLint internal_format = 0;
    std::string key;
  } cache_;
  std::string drawn_key_;  // what the output of the last call holds (empty: unknown)
};

}  // namespace

AQ_NODE(kPigmentCanvasNode, PigmentCanvas, "pigment_canvas", "Watercolor",
        "The pigment densities of the view (turbulence, dispersion, paper) on the dynamic "
        "canvas, as n + 0.5 in r, g, b, for pigment_apply; kept while the view stays.",
        0, kInputs, kOutputs, kParams);

const aq_node_desc* pigment_canvas_node_desc() {
  return &kPigmentCanvasNode;
}
