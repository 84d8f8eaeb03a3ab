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
#include <aquarelle/sdk/static_layer.hpp>

#include <array>
#include <cstdio>
#include <string>

#include "pigment_shaders.h"
#include "pigment_shared.h"

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
    pigment::kSeedParam,
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

    // 0: the densities cannot be kept (cache off, an input of unknown content).
    const uint64_t key = cache_key(ctx, out, canvas, params, defines);
    // The host handed back the very texture this call's densities went into last time.
    // Nothing changed in it then (damage tracking: its readers redraw nothing for it).
    if (key != 0 && ctx.output_kept(0) && drawn_ == key)
      return ctx.set_output_damage(0, aq::Region()) ? AQ_OK : AQ_ERROR;
    drawn_ = 0;
    aq_image stand_in;  // names a complete texture for the samplers pass 1 does not read
    if (!ctx.scratch(1, 1, AQ_FORMAT_RGBA8, &stand_in)) return AQ_ERROR;
    const std::string text = defines + shaders::pigment_frag.text;
    const aq_shader_source fragment{shaders::pigment_frag.name, text.c_str(), nullptr};
    // Binds the program and what pass 1 reads; the caller binds the target and draws.
    auto prepare = [&]() -> bool {
      const GLuint program = ctx.program(fragment);
      if (program == 0) return false;
      glUseProgram(program);
      pigment::set_canvas_uniforms(program, params, static_cast<double>(width) / height, canvas);
      pigment::bind_density_textures(ctx, program, kTurbulence, stand_in.texture);
      aq::bind_texture(program, "u_image", 0, stand_in);
      aq::bind_texture(program, "u_position", 4, stand_in);
      return true;
    };
    if (key != 0) kept_.ensure(ctx.raw()->gl_generation, &out, 1, nullptr);
    if (key != 0 && kept_.key != key && kept_.bind()) {
      if (!prepare()) return AQ_ERROR;
      ctx.raw()->host->draw_fullscreen(ctx.raw()->host_data);
      aq::unbind_textures(5);
      kept_.key = key;
    }
    if (key != 0 && kept_.key == key) {
      kept_.copy_to(&out, 1, nullptr);
      drawn_ = key;
      return AQ_OK;
    }
    // Not kept (cache off, an input of unknown content): straight into the output.
    if (!prepare()) return AQ_ERROR;
    const bool drawn = ctx.draw(out);
    aq::unbind_textures(5);
    return drawn ? AQ_OK : AQ_ERROR;
  }

 private:
  // A hash of everything the densities depend on; 0 when they cannot be kept (cache off, or a
  // connected image whose content the host does not identify).
  static uint64_t cache_key(aq::Context& ctx, const aq_image& out, const pigment::Canvas& canvas,
                            const pigment::DensityParams& params, const std::string& defines) {
    if (!ctx.param_bool(kCache)) return 0;
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
      if (input == 0) return 0;
      key += std::to_string(i) + ":" + std::to_string(input) + "|";
    }
    aq::Fnv1a hashed;
    hashed.mix(key.data(), key.size());
    return hashed.value != 0 ? hashed.value : 1;
  }

  aq::CachedTargets kept_;  // the densities of the key kept_.key
  uint64_t drawn_ = 0;      // the key of what the last call's output holds (0: unknown)
};

}  // namespace

AQ_NODE(kPigmentCanvasNode, PigmentCanvas, "pigment_canvas", "Watercolor",
        "The pigment densities of the view (turbulence, dispersion, paper) on the dynamic "
        "canvas, as n + 0.5 in r, g, b, for pigment_apply; kept while the view stays.",
        0, kInputs, kOutputs, kParams);

const aq_node_desc* pigment_canvas_node_desc() {
  return &kPigmentCanvasNode;
}
