// layered: Luft & Deussen's layered watercolor (seeds 003 and 004): the g-buffer is segmented
// into one layer per object, each layer is lit, abstracted, given wet edges, edge darkening
// and granulation, and the layers are glazed onto the paper far to near with pigment mixing
// and a blurred depth test. README.md has the maths of every step.
//
//   id, depth, albedo ─► readback ─► table: ids present, far to near, light/dark colour each
//                                        │ ranges of 4 ids (one RGBA channel per object)
//   paper ─► paper pass ─► under         ▼
//   per range:  segment+light (MRT) ─► intensity, diffuse, depth   (4 objects per texture)
//               shared Gaussian ×3 ─► abstraction blur (aquarelle/sdk/gaussian_blur.hpp) 3x3
//               Laplacian + threshold ─► edges ─► Gaussian ─► wet-edge widths composite: glaze the
//               4 layers over `under` ─► under (ping-pong) ... ─► image
//
// Why packed channels: a texture array or one texture per id would make every later step one
// pass per id; four objects per RGBA texture let each pass (segment, blur, edges, composite)
// serve four objects, the shared Gaussian blurs four masks at once, ids absent from the frame
// cost nothing (only the ids found are packed), memory stays at 11 textures whatever the id
// count (ranges run one after the other), and ranges sorted far to near make the per-range
// composite a painter's algorithm across ranges too. 8 colour attachments would pack 32 ids
// per pass but every later pass reads at most 4 channels per texture fetch anyway.
#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/gaussian_blur.hpp>
#include <aquarelle/sdk/scene_math.hpp>
#include <aquarelle/sdk/view_bounds.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "fast_layers.h"
#include "layer_packing.h"
#include "layer_table.h"
#include "layered_params.h"
#include "layered_shaders.h"

namespace {

using namespace layered;  // the Input and Param indices (layered_params.h)

constexpr aq_port_desc kInputs[] = {
    aq::image_port("id", "object id per pixel (gbuffer.id, R32F); 0 on the background"),
    aq::image_port("normal", "world normal (gbuffer.normal)"),
    aq::image_port("albedo", "base colour (gbuffer.albedo): each object's mean is its pigment"),
    aq::image_port("depth", "linear view depth (gbuffer.depth); 0 on the background"),
    aq::optional_image_port("paper", "paper height in r (mean 0.5), e.g. the paper node"),
    aq::optional_scene_port("scene", "light and camera (else the light/view parameters)"),
    aq::optional_image_port("position", "world position (gbuffer.position): for `shadow`"),
    aq::optional_image_port("shadow",
                            "light-space depth (shadowmap.depth): soft shadows, with `position` "
                            "and `scene`")};
constexpr aq_port_desc kOutputs[] = {aq::image_port("image", "the painting")};

constexpr aq_param_desc kParams[] = {
    aq::enum_param("mixing", "rgb|cmyk|kubelka_munk", 2,
                   "how colours interpolate and glaze: rgb (as light, for comparison), cmyk "
                   "(seed 004's lerp in CMYK), kubelka_munk (pigments, Curtis et al. 1997)"),
    aq::enum_param("view", "painting|segments|lighting|abstraction|edges", 0,
                   "painting: every step; segments: the flat masks; lighting: the lit layers "
                   "with highlights removed; abstraction: blurred and cut shapes; edges: the "
                   "wet-edge weights"),
    aq::vec3_param("light_direction", 0.5, -0.7, -0.5, -1, 1,
                   "direction the light travels (world) when no scene is connected"),
    aq::vec3_param("view_direction", 0.0, 0.0, 1.0, -1, 1,
                   "direction towards the viewer (world) when no scene is connected"),
    aq::float_param("shininess", 40.0, 1.0, 1000.0, "Blinn-Phong specular exponent", 0.0, "log"),
    aq::float_param("specular_threshold", 0.6, 0.0, 1.0,
                    "specular at or above this is left as paper white (1: no highlights)"),
    aq::float_param("light_density", 0.6, 0.05, 4.0,
                    "pigment concentration of the lit wash: light = albedo^light_density"),
    aq::float_param("dark_density", 1.8, 0.05, 8.0,
                    "pigment concentration of the unlit wash: dark = albedo^dark_density"),
    aq::string_param("palette", "",
                     "per-object colours overriding the albedo: 'ID:R,G,B[:R,G,B]; ...' (light, "
                     "then optionally dark)"),
    aq::float_param("gooch", 0.35, 0.0, 1.0,
                    "Gooch shading: light mixed towards `warm`, dark towards `cool` (pigments)"),
    aq::color_param("warm", 0.95, 0.75, 0.3, "Gooch warm colour"),
    aq::color_param("cool", 0.15, 0.25, 0.6, "Gooch cool colour"),
    aq::float_param("abstraction_sigma", 3.0, 0.0, 64.0,
                    "Gaussian sigma (output pixels) that simplifies each object's shape"),
    aq::float_param("threshold", 0.5, 0.05, 0.95,
                    "level of the blurred mask where the wash ends: lower grows the shapes"),
    aq::float_param("softness", 0.08, 0.0, 0.5, "half-width of the smooth step at the wash edge"),
    aq::enum_param("wet_edges", "wet_to_dry|wet_in_wet|none", kWetToDry,
                   "wet_to_dry: a darker rim inside each shape; wet_in_wet: the colour feathers "
                   "out into the paper; none"),
    aq::string_param("wet_in_wet_ids", "",
                     "ids painted wet-in-wet whatever wet_edges says (spaces or commas)"),
    aq::float_param("edge_threshold", 0.1, 0.001, 4.0,
                    "3x3 Laplacian response of the shape where an edge starts (full at 2x)"),
    aq::float_param("edge_width", 2.5, 0.0, 32.0,
                    "Gaussian sigma (output pixels) widening the detected edges"),
    aq::float_param("edge_darkness", 0.8, 0.0, 4.0,
                    "extra pigment of the wet-to-dry rim (translucent darker layer)"),
    aq::float_param("wet_spread", 0.7, 0.0, 1.0, "coverage of the wet-in-wet feather outside"),
    aq::float_param("edge_darkening", 0.5, 0.0, 4.0,
                    "extra pigment from the inverted blur of the mask (seed 004)"),
    aq::float_param("edge_noise", 0.08, 0.0, 0.4,
                    "amplitude of the noise that moves the wash edge (edge modulation)"),
    aq::float_param("noise_scale", 24.0, 1.0, 4096.0,
                    "size (output pixels) of a cell of the edge-modulation noise", 0.0, "log"),
    aq::float_param("granulation", 0.6, 0.0, 1.0,
                    "paper height inverted into pigment opacity: more pigment in the dips"),
    aq::color_param("paper_color", 0.98, 0.96, 0.9, "colour of the paper (multiplied in)"),
    aq::float_param("paper_relief", 0.25, 0.0, 1.0, "shading of the paper by its height"),
    aq::float_param("depth_band", 0.3, 0.0, 1000.0,
                    "blurred depth test: depth (scene units) over which a layer behind "
                    "another fades out"),
    aq::float_param("density", 1.0, 0.0, 4.0, "pigment thickness of every wash"),
    aq::float_param("thin_shapes", 1.0, 0.0, 1.0,
                    "keeps shapes thinner than the abstraction blur (a blade, a stem) that the "
                    "threshold would erase: 1 keeps them whole, 0 lets them vanish"),
    aq::float_param("shadows", 0.8, 0.0, 4.0,
                    "pigment of the soft shadow layer (blurred depth test against the `shadow` "
                    "input; 0: none)"),
    aq::float_param("shadow_softness", 4.0, 0.0, 64.0,
                    "Gaussian sigma (output pixels) of the shadow layer: the penumbra"),
    aq::float_param("shadow_band", 0.05, 0.0, 1000.0,
                    "depth (scene units) behind its occluder over which a surface passes from "
                    "semi-visible to fully shadowed"),
    aq::color_param("shadow_color", 0.35, 0.4, 0.6, "pigment of the shadow glaze (cool)"),
    aq::enum_param(
        "method", "exact|fast", kFast,
        "fast (default): all layers at once at a quarter (abstraction_sigma >= 2.24 px) or "
        "half resolution with a short list of the four nearest layers per texel, no "
        "readback (README: Fast method; an approximation, its error against exact in the "
        "bench); exact: every layer at full size, as the CPU reference")};

constexpr int kLayersPerRange = 4;

// A pixel rectangle, inclusive; passes draw only inside it (scissor) where nothing else can
// change (README: "Only where the range can paint").
struct Rect {
  int x0, y0, x1, y1;
  Rect grown(int by, int width, int height) const {
    return {std::max(0, x0 - by), std::max(0, y0 - by), std::min(width - 1, x1 + by),
            std::min(height - 1, y1 + by)};
  }
  void scissor() const { glScissor(x0, y0, x1 - x0 + 1, y1 - y0 + 1); }
};

std::string define(const char* name, int64_t value) {
  return "#define " + std::string(name) + " " + std::to_string(value) + "\n";
}

bool finite3(const double* v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

void normalise(double v[3], const double fallback[3]) {
  const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(len > 1e-12) || !std::isfinite(len)) {
    for (int k = 0; k < 3; ++k) v[k] = fallback[k];
    return;
  }
  for (int k = 0; k < 3; ++k) v[k] /= len;
}

struct Layered {
  // Composed shader texts (the host compiles them at once and caches by text).
  std::string segment_text, edges_text, paper_text, composite_text, peak_text, colours_text,
      shadow_text;
  aq::view_bounds::MeshBoxes mesh_boxes;  // the scene's mesh boxes, for the shadow map's fit
  layered::FastLayers fast;
  std::vector<float> id_pixels, depth_pixels, albedo_pixels, owner_pixels, table_pixels;

  // What the passes of one frame share.
  struct Frame {
    int w = 0, h = 0;
    std::vector<layered::Layer> layers;
    std::vector<int> channel;  // per layer: range channel / 4, RGBA channel % 4
    size_t range_count = 0;
    double light[3] = {0, 1, 0}, half[3] = {0, 1, 0};
    double sigma = 0.0, edge_sigma = 0.0;
    int reach_a = 0, reach_e = 0, reach_peak = 0;
    bool thin = false;
    bool whole = false, run_edges = false, has_paper = false, has_shadow = false;
    int64_t wet_edges = kWetToDry;
    std::vector<layered::PaletteEntry> palette;
    std::vector<float> wet_ids;
    GLuint segment = 0, edge = 0, paper = 0, composite = 0, peak_program = 0, colours_program = 0,
           shadow_program = 0;
    aq_image intensity{}, diffuse{}, depth{}, blur_intensity{}, blur_diffuse{}, blur_depth{},
        edges{}, blur_edges{}, horizontal{}, under[2]{}, out{}, owner{}, table{}, peak{}, colours{},
        shadow_raw{}, shadow_blur{};
  };

  // The boxes each pass of a range fills around one of its layers (see range_rects).
  struct RangeRects {
    Rect paint, blurred, blurred_rows, segmented, edge_rect, edge_rows, peak_rows;
  };

  // The texture's first `components` channels as floats; false on a GL error.
  static bool read_back(const aq_image& image, GLenum format, int components,
                        std::vector<float>& pixels) {
    pixels.assign(static_cast<size_t>(image.width) * image.height * components, 0.0f);
    while (glGetError() != GL_NO_ERROR) {
    }  // only this read's error counts below
    glGetTextureImage(image.texture, 0, format, GL_FLOAT,
                      static_cast<GLsizei>(pixels.size() * sizeof(float)), pixels.data());
    return glGetError() == GL_NO_ERROR;
  }

  std::string compose(const std::string& defines, const aq_shader_source& main,
                      const char* includes) {
    return defines + includes + shaders::layered_common_glsl.text + "\n#line 1\n" + main.text;
  }

  int process(aq::Context& ctx) {
    bool ran_fast = false;
    const int result = paint(ctx, ran_fast);
    // The fast method keeps a texture drawn from the paper, trusting the paper's damage since
    // the node's last call: a call that did not run it makes it forget that texture.
    if (!ran_fast) fast.forget_kept();
    return result;
  }

  int paint(aq::Context& ctx, bool& ran_fast) {
    Frame f;
    if (!check_sizes(ctx) || !shadow_inputs(ctx, f) || !parse_settings(ctx, f)) return AQ_ERROR;
    light_and_view(ctx, f);
    if (ctx.param_enum(kMethod) == kFast && ctx.param_enum(kView) == 0 &&
        layered::FastLayers::applies(f.sigma, f.edge_sigma)) {
      ran_fast = true;
      return run_fast(ctx, f) ? AQ_OK : AQ_ERROR;
    }
    if (!build_layers(ctx, f)) return AQ_ERROR;
    plan_ranges(f);
    if (!allocate(ctx, f) || !compile(ctx, f)) return AQ_ERROR;
    bool ok = paint_paper(ctx, f);
    // The ping-pong textures agree everywhere but in the box the last range painted, which is
    // copied across before the next range paints its own box (so only the last composite
    // covers the whole image).
    std::vector<Rect> last_paint;
    if (f.range_count > 0) ok = ok && gooch_colours(ctx, f);
    if (f.range_count > 0 && f.has_shadow) {
      ok = ok && shadow_layer(ctx, f, ctx.param_float(kShadowSoftness) * ctx.render_scale());
    }
    for (size_t r = 0; ok && r < f.range_count; ++r) ok = run_range(ctx, f, r, last_paint);
    glDisable(GL_SCISSOR_TEST);
    aq::unbind_textures(15);
    return ok ? AQ_OK : AQ_ERROR;
  }

  // The fast method (fast_layers.h): no readback, a fixed number of passes; the shadow layer
  // as the exact method makes it.
  bool run_fast(aq::Context& ctx, Frame& f) {
    f.has_paper = ctx.connected(kPaper);
    if (!ctx.output_like(0, ctx.input_image(kId), &f.out)) return false;
    if (f.has_shadow) {
      // The shadow layer at the lists' resolution: averaged there, blurred there, divided
      // after the composite's bilinear enlargement (README "Fast method").
      const int d = layered::FastLayers::divisor_for(f.sigma);
      const int lw = (f.w + d - 1) / d, lh = (f.h + d - 1) / d;
      const uint32_t f32 = AQ_FORMAT_RGBA32F;
      if (!ctx.scratch(lw, lh, f32, &f.shadow_raw) || !ctx.scratch(lw, lh, f32, &f.shadow_blur) ||
          !ctx.scratch(lw, lh, f32, &f.horizontal) ||
          !compile_shadow(ctx, f, shaders::layered_fast_shadow_frag, d) ||
          !shadow_layer(ctx, f,
                        layered::FastLayers::low_sigma(
                            ctx.param_float(kShadowSoftness) * ctx.render_scale(), d))) {
        return false;
      }
    }
    layered::FastFrame ff;
    ff.w = f.w;
    ff.h = f.h;
    std::copy(f.light, f.light + 3, ff.light);
    std::copy(f.half, f.half + 3, ff.half);
    ff.sigma = f.sigma;
    ff.edge_sigma = f.edge_sigma;
    ff.run_edges = f.run_edges;
    ff.thin = f.thin;
    ff.has_paper = f.has_paper;
    ff.has_shadow = f.has_shadow;
    ff.wet_default = f.wet_edges == kWetInWet;
    ff.palette = f.palette;
    ff.wet_ids = f.wet_ids;
    ff.shadow_raw = f.shadow_raw;
    ff.shadow_blur = f.shadow_blur;
    ff.out = f.out;
    return fast.run(ctx, ff);
  }

  // The exact method's per-pixel shadow pass, or with `divisor` > 1 the fast method's average
  // over divisor x divisor pixels.
  bool compile_shadow(aq::Context& ctx, Frame& f, const aq_shader_source& main, int divisor) {
    const std::string defines =
        define("AQ_HAS_PAPER", f.has_paper ? 1 : 0) + define("AQ_HAS_SHADOW", 1) +
        define("AQ_MIX_MODE", ctx.param_enum(kMixing)) + define("AQ_VIEW", ctx.param_enum(kView)) +
        define("AQ_DIVISOR", divisor);
    shadow_text = compose(defines, main, shaders::layered_shadow_glsl.text);
    f.shadow_program = ctx.program({main.name, shadow_text.c_str(), nullptr});
    return f.shadow_program != 0;
  }

  static bool check_sizes(aq::Context& ctx) {
    const aq_image id = ctx.input_image(0);
    const char* names[] = {"id", "normal", "albedo", "depth"};
    for (uint32_t i = 1; i < 4; ++i) {
      const aq_image other = ctx.input_image(i);
      if (other.width != id.width || other.height != id.height) {
        ctx.fail(std::string("layered '") + ctx.node_id() + "': input '" + names[i] + "' is " +
                 std::to_string(other.width) + "x" + std::to_string(other.height) +
                 " but 'id' is " + std::to_string(id.width) + "x" + std::to_string(id.height) +
                 ": connect the id, normal, albedo and depth of one gbuffer");
        return false;
      }
    }
    return true;
  }

  // Soft shadows need the map, the positions it is looked up at and the scene's light matrix.
  static bool shadow_inputs(aq::Context& ctx, Frame& f) {
    f.has_shadow = false;
    if (!ctx.connected(kShadow) || !(ctx.param_float(kShadows) > 0.0)) return true;
    if (!ctx.connected(kPosition) || ctx.input_scene(kScene) == nullptr) {
      ctx.fail(std::string("layered '") + ctx.node_id() +
               "': input 'shadow' is connected but 'position' or 'scene' is not: the shadow "
               "map is looked up at the gbuffer's world positions with the scene's light; "
               "connect gbuffer.position and the scene (or disconnect 'shadow')");
      return false;
    }
    const aq_image id = ctx.input_image(kId), position = ctx.input_image(kPosition);
    if (position.width != id.width || position.height != id.height) {
      ctx.fail(std::string("layered '") + ctx.node_id() + "': input 'position' is " +
               std::to_string(position.width) + "x" + std::to_string(position.height) +
               " but 'id' is " + std::to_string(id.width) + "x" + std::to_string(id.height) +
               ": connect the position of the same gbuffer");
      return false;
    }
    f.has_shadow = true;
    return true;
  }

  // The per-object table: ids present far to near, their colours and boxes (one readback).
  // The size, the per-id lists of the parameters and which passes run.
  static bool parse_settings(aq::Context& ctx, Frame& f) {
    const aq_image id = ctx.input_image(kId);
    f.w = id.width;
    f.h = id.height;
    for (const auto& [param, error] :
         {std::pair{"palette", layered::parse_palette(ctx.param_string(kPalette), &f.palette)},
          std::pair{"wet_in_wet_ids",
                    layered::parse_id_list(ctx.param_string(kWetInWetIds), &f.wet_ids)}}) {
      if (!error.empty()) {
        ctx.fail(std::string("layered '") + ctx.node_id() + "': parameter '" + param +
                 "': " + error);
        return false;
      }
    }
    f.wet_edges = ctx.param_enum(kWetEdges);
    const int64_t view_mode = ctx.param_enum(kView);
    f.run_edges =
        (f.wet_edges != kNoWetEdges || !f.wet_ids.empty()) && (view_mode == 0 || view_mode == 4);
    const double scale = ctx.render_scale();
    f.sigma = ctx.param_float(kAbstractionSigma) * scale;
    f.edge_sigma = ctx.param_float(kEdgeWidth) * scale;
    f.thin = ctx.param_float(kThinShapes) > 0.0 && f.sigma > 0.0;
    return true;
  }

  // The per-object table: ids present far to near, their colours and boxes (one readback).
  bool build_layers(aq::Context& ctx, Frame& f) {
    const aq_image id = ctx.input_image(kId);
    if (!read_back(id, GL_RED, 1, id_pixels) ||
        !read_back(ctx.input_image(3), GL_RED, 1, depth_pixels) ||
        !read_back(ctx.input_image(2), GL_RGBA, 4, albedo_pixels)) {
      ctx.fail(std::string("layered '") + ctx.node_id() +
               "': reading the id, depth and albedo inputs back failed: connect float "
               "images (the gbuffer's id, depth and albedo outputs)");
      return false;
    }
    f.layers = layered::collect_layers(id_pixels.data(), depth_pixels.data(), albedo_pixels.data(),
                                       id_pixels.size(), id.width);
    layered::ColourSettings colours;
    colours.light_density = ctx.param_float(kLightDensity);
    colours.dark_density = ctx.param_float(kDarkDensity);
    colours.wet_in_wet_default = f.wet_edges == kWetInWet;
    layered::assign_colours(f.layers, colours, f.palette, f.wet_ids);
    return true;
  }

  static void light_and_view(aq::Context& ctx, Frame& f) {
    double view[3];
    const aq_scene* scene = ctx.input_scene(5);
    const double* light_param = ctx.param_vec3(kLightDirection);
    const double* view_param = ctx.param_vec3(kViewDirection);
    for (int k = 0; k < 3; ++k) {
      f.light[k] = scene ? -static_cast<double>(scene->light.direction[k]) : -light_param[k];
      view[k] = scene ? static_cast<double>(scene->camera.position[k]) - scene->camera.target[k]
                      : view_param[k];
    }
    const double up[3] = {0.0, 1.0, 0.0}, towards_viewer[3] = {0.0, 0.0, 1.0};
    if (!finite3(f.light)) std::copy(up, up + 3, f.light);
    if (!finite3(view)) std::copy(towards_viewer, towards_viewer + 3, view);
    normalise(f.light, up);
    normalise(view, towards_viewer);
    for (int k = 0; k < 3; ++k) f.half[k] = f.light[k] + view[k];
    normalise(f.half, f.light);
  }

  // Reaches of the kernels and the channel of every layer (layer_packing.h): objects far
  // enough apart share a channel, so the range count follows the overlap, not the objects.
  static void plan_ranges(Frame& f) {
    f.reach_a = static_cast<int>(std::ceil(aq::gaussian::kTruncationSigmas * f.sigma)) + 1;
    f.reach_e =
        f.run_edges
            ? static_cast<int>(std::ceil(aq::gaussian::kTruncationSigmas * f.edge_sigma)) + 1
            : 0;
    f.reach_peak = f.thin ? static_cast<int>(std::ceil(f.sigma)) + 1 : 0;
    f.whole = 2 * std::max({f.reach_a, f.reach_e, f.reach_peak}) >= std::min(f.w, f.h) - 1;
    f.channel = layered::assign_channels(
        f.layers, f.whole ? -1 : layered::channel_gap(f.reach_a, f.reach_e) + 2 * f.reach_peak);
    int channels = 0;
    for (int c : f.channel) channels = std::max(channels, c + 1);
    f.range_count = static_cast<size_t>((channels + kLayersPerRange - 1) / kLayersPerRange);
  }

  // 14 textures whatever the number of objects, and the per-layer table (id, wet; light; dark).
  bool allocate(aq::Context& ctx, Frame& f) {
    if (!ctx.output_like(0, ctx.input_image(0), &f.out)) return false;
    if (f.range_count == 0) return true;  // an empty frame is just the paper
    const uint32_t f32 = AQ_FORMAT_RGBA32F;
    for (aq_image* t :
         {&f.intensity, &f.diffuse, &f.depth, &f.blur_intensity, &f.blur_diffuse, &f.blur_depth,
          &f.edges, &f.blur_edges, &f.horizontal, &f.under[0], &f.under[1], &f.owner, &f.peak}) {
      if (!ctx.scratch(f.w, f.h, f32, t)) return false;
    }
    if (f.has_shadow && (!ctx.scratch(f.w, f.h, f32, &f.shadow_raw) ||
                         !ctx.scratch(f.w, f.h, f32, &f.shadow_blur))) {
      return false;
    }
    const int n = static_cast<int>(f.layers.size());
    if (!ctx.scratch(n, 3, f32, &f.table) || !ctx.scratch(n, 2, f32, &f.colours)) return false;
    table_pixels.assign(static_cast<size_t>(n) * 3 * 4, 0.0f);
    for (int i = 0; i < n; ++i) {
      const layered::Layer& layer = f.layers[i];
      float* row0 = &table_pixels[4 * i];
      float* row1 = &table_pixels[4 * (n + i)];
      float* row2 = &table_pixels[4 * (2 * n + i)];
      row0[0] = layer.id;
      row0[1] = layer.wet_in_wet ? 1.0f : 0.0f;
      row0[2] = static_cast<float>(f.channel[i] / kLayersPerRange);  // its range
      for (int c = 0; c < 3; ++c) {
        row1[c] = static_cast<float>(layer.light[c]);
        row2[c] = static_cast<float>(layer.dark[c]);
      }
    }
    glTextureSubImage2D(f.table.texture, 0, 0, 0, n, 3, GL_RGBA, GL_FLOAT, table_pixels.data());
    // The owner image comes from the pool with what an earlier call left: zero it once per
    // frame (the last range's composite reads it everywhere).
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearTexImage(f.owner.texture, 0, GL_RGBA, GL_FLOAT, zero);
    return true;
  }

  bool compile(aq::Context& ctx, Frame& f) {
    f.has_paper = ctx.connected(kPaper);
    const std::string defines = define("AQ_HAS_PAPER", f.has_paper ? 1 : 0) +
                                define("AQ_HAS_SHADOW", f.has_shadow ? 1 : 0) +
                                define("AQ_MIX_MODE", ctx.param_enum(kMixing)) +
                                define("AQ_VIEW", ctx.param_enum(kView));
    segment_text = compose(defines, shaders::layered_segment_frag, "");
    edges_text =
        compose(defines, shaders::layered_edges_frag, "#include \"aquarelle/edge_kernels.glsl\"\n");
    paper_text = compose(defines, shaders::layered_paper_frag, "");
    composite_text =
        compose(defines, shaders::layered_composite_frag, "#include \"aquarelle/pigment.glsl\"\n");
    f.segment = ctx.program({"layered_segment.frag", segment_text.c_str(), nullptr});
    f.edge = ctx.program({"layered_edges.frag", edges_text.c_str(), nullptr});
    f.paper = ctx.program({"layered_paper.frag", paper_text.c_str(), nullptr});
    f.composite = ctx.program({"layered_composite.frag", composite_text.c_str(), nullptr});
    peak_text = compose(defines, shaders::layered_peak_frag, "");
    f.peak_program = ctx.program({"layered_peak.frag", peak_text.c_str(), nullptr});
    colours_text =
        compose(defines, shaders::layered_colours_frag, "#include \"aquarelle/pigment.glsl\"\n");
    f.colours_program = ctx.program({"layered_colours.frag", colours_text.c_str(), nullptr});
    if (f.colours_program == 0) return false;
    if (f.has_shadow && !compile_shadow(ctx, f, shaders::layered_shadow_frag, 1)) return false;
    return f.segment != 0 && f.edge != 0 && f.paper != 0 && f.composite != 0 && f.peak_program != 0;
  }

  static bool paint_paper(aq::Context& ctx, const Frame& f) {
    glUseProgram(f.paper);
    if (f.has_paper) aq::bind_texture(f.paper, "u_paper", 0, ctx.input_image(4));
    aq::set_vec3(f.paper, "u_paper_color", ctx.param_vec3(kPaperColor));
    aq::set_float(f.paper, "u_paper_relief", ctx.param_float(kPaperRelief));
    aq::set_vec2(f.paper, "u_size", f.w, f.h);
    if (f.range_count == 0) return ctx.draw(f.out);
    if (!ctx.bind_targets(f.under, 2)) return false;
    ctx.raw()->host->draw_fullscreen(ctx.raw()->host_data);
    return true;
  }

  // Where a layer paints: its box grown by the abstraction's reach (everywhere when the
  // kernels are wider than the image).
  static Rect paint_box(const Frame& f, const layered::Layer& layer) {
    if (f.whole) return {0, 0, f.w - 1, f.h - 1};
    return Rect{layer.x0, layer.y0, layer.x1, layer.y1}.grown(f.reach_a, f.w, f.h);
  }

  // The owner image of range r: per channel, 1 + the index of the layer painting there (0:
  // none), over each of the range's `segmented` rects (the largest areas its passes read).
  void upload_owner(const Frame& f, size_t r, const std::vector<RangeRects>& rects) {
    owner_pixels.resize(static_cast<size_t>(f.w) * f.h * 4);
    for (const RangeRects& rr : rects) {
      const Rect& rect = rr.segmented;
      for (int y = rect.y0; y <= rect.y1; ++y) {
        float* row = &owner_pixels[4 * (static_cast<size_t>(y) * f.w + rect.x0)];
        std::fill(row, row + 4 * (rect.x1 - rect.x0 + 1), 0.0f);
      }
    }
    for (size_t i = 0; i < f.layers.size(); ++i) {
      if (static_cast<size_t>(f.channel[i]) / kLayersPerRange != r) continue;
      const int k = f.channel[i] % kLayersPerRange;
      const Rect box = paint_box(f, f.layers[i]);
      for (int y = box.y0; y <= box.y1; ++y) {
        for (int x = box.x0; x <= box.x1; ++x) {
          owner_pixels[4 * (static_cast<size_t>(y) * f.w + x) + k] = static_cast<float>(i + 1);
        }
      }
    }
    glPixelStorei(GL_UNPACK_ROW_LENGTH, f.w);
    for (const RangeRects& rr : rects) {
      const Rect& rect = rr.segmented;
      glTextureSubImage2D(f.owner.texture, 0, rect.x0, rect.y0, rect.x1 - rect.x0 + 1,
                          rect.y1 - rect.y0 + 1, GL_RGBA, GL_FLOAT,
                          &owner_pixels[4 * (static_cast<size_t>(rect.y0) * f.w + rect.x0)]);
    }
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  }

  // (RangeRects:) the boxes each pass fills around one layer so the next pass reads only what it
  // wrote this range (README: "Only where the range can paint"). A range draws each pass once per
  // layer box: the work follows the pixels the layers cover, not the box around them all. A pixel
  // in two boxes is drawn twice with the same result (every pass reads other textures than it
  // writes).
  static std::vector<RangeRects> range_rects(const Frame& f, size_t r) {
    const Rect full{0, 0, f.w - 1, f.h - 1};
    if (f.whole) return {{full, full, full, full, full, full, full}};
    std::vector<Rect> boxes;
    for (size_t i = 0; i < f.layers.size(); ++i) {
      if (static_cast<size_t>(f.channel[i]) / kLayersPerRange == r) {
        boxes.push_back(paint_box(f, f.layers[i]));
      }
    }
    merge_overlapping(boxes);
    std::vector<RangeRects> out;
    for (const Rect& paint : boxes) {
      RangeRects rr;
      rr.paint = paint;
      rr.blurred = rr.paint.grown(std::max(2 * f.reach_e + 1, f.reach_peak), f.w, f.h);
      rr.blurred_rows = rr.blurred.grown(f.reach_a, f.w, f.h);
      rr.segmented = rr.blurred_rows.grown(f.reach_a, f.w, f.h);
      rr.edge_rect = rr.paint.grown(2 * f.reach_e, f.w, f.h);
      rr.edge_rows = rr.paint.grown(f.reach_e, f.w, f.h);
      rr.peak_rows = rr.paint.grown(f.reach_peak, f.w, f.h);
      out.push_back(rr);
    }
    return out;
  }

  // Boxes of one range overlap where layers of different channels meet: two boxes whose
  // bounding box is no larger than their areas together become that box, so no pixel is drawn
  // many times over.
  static void merge_overlapping(std::vector<Rect>& boxes) {
    auto area = [](const Rect& b) {
      return static_cast<int64_t>(b.x1 - b.x0 + 1) * (b.y1 - b.y0 + 1);
    };
    for (bool merged = true; merged;) {
      merged = false;
      for (size_t i = 0; i < boxes.size() && !merged; ++i) {
        for (size_t j = i + 1; j < boxes.size() && !merged; ++j) {
          const Rect u{std::min(boxes[i].x0, boxes[j].x0), std::min(boxes[i].y0, boxes[j].y0),
                       std::max(boxes[i].x1, boxes[j].x1), std::max(boxes[i].y1, boxes[j].y1)};
          if (area(u) <= area(boxes[i]) + area(boxes[j])) {
            boxes[i] = u;
            boxes.erase(boxes.begin() + static_cast<std::ptrdiff_t>(j));
            merged = true;
          }
        }
      }
    }
  }

  // Runs `draw` once per layer box of the range, scissored to that box's `which` rect.
  template <class Draw>
  static bool each(const std::vector<RangeRects>& rects, Rect RangeRects::*which, Draw draw) {
    for (const RangeRects& rr : rects) {
      (rr.*which).scissor();
      if (!draw()) return false;
    }
    return true;
  }

  bool run_range(aq::Context& ctx, const Frame& f, size_t r, std::vector<Rect>& last_paint) {
    const std::vector<RangeRects> rects = range_rects(f, r);
    upload_owner(f, r, rects);
    glEnable(GL_SCISSOR_TEST);
    // Segmentation and lighting, four channels (any number of objects) at once.
    glUseProgram(f.segment);
    aq::bind_texture(f.segment, "u_id", 0, ctx.input_image(0));
    aq::bind_texture(f.segment, "u_normal", 1, ctx.input_image(1));
    aq::bind_texture(f.segment, "u_depth", 2, ctx.input_image(3));
    aq::bind_texture(f.segment, "u_owner", 3, f.owner);
    aq::bind_texture(f.segment, "u_table", 4, f.table);
    aq::set_vec3(f.segment, "u_light", f.light);
    aq::set_vec3(f.segment, "u_half", f.half);
    aq::set_float(f.segment, "u_shininess", ctx.param_float(kShininess));
    aq::set_float(f.segment, "u_specular_threshold", ctx.param_float(kSpecularThreshold));
    const aq_image targets[3] = {f.intensity, f.diffuse, f.depth};
    if (!ctx.bind_targets(targets, 3)) return false;
    each(rects, &RangeRects::segmented, [&] {
      ctx.raw()->host->draw_fullscreen(ctx.raw()->host_data);
      return true;
    });
    aq::unbind_textures(5);

    // Abstraction: the shared Gaussian.
    for (auto [in, blurred_out] :
         {std::pair{f.intensity, f.blur_intensity}, std::pair{f.diffuse, f.blur_diffuse},
          std::pair{f.depth, f.blur_depth}}) {
      if (!each(rects, &RangeRects::blurred_rows,
                [&] { return aq::gaussian::blur_pass(ctx, in, f.horizontal, f.sigma, 0); }) ||
          !each(rects, &RangeRects::blurred, [&] {
            return aq::gaussian::blur_pass(ctx, f.horizontal, blurred_out, f.sigma, 1);
          })) {
        return false;
      }
    }

    // Wet edges: 3x3 Laplacian and threshold, widened by the Gaussian.
    if (f.run_edges) {
      glUseProgram(f.edge);
      aq::bind_texture(f.edge, "u_blurred", 0, f.blur_intensity);
      set_common(ctx, f.edge);
      aq::set_float(f.edge, "u_edge_threshold", ctx.param_float(kEdgeThreshold));
      if (!each(rects, &RangeRects::edge_rect, [&] { return ctx.draw(f.edges); }) ||
          !each(rects, &RangeRects::edge_rows,
                [&] {
                  return aq::gaussian::blur_pass(ctx, f.edges, f.horizontal, f.edge_sigma, 0);
                }) ||
          !each(rects, &RangeRects::paint, [&] {
            return aq::gaussian::blur_pass(ctx, f.horizontal, f.blur_edges, f.edge_sigma, 1);
          })) {
        return false;
      }
    }
    if (f.thin && !peaks(ctx, f, rects)) return false;
    return composite_range(ctx, f, r, rects, last_paint);
  }

  // Thin shapes: each layer's peak blurred intensity over a (2r+1)^2 window, r = ceil(σa) + 1.
  static bool peaks(aq::Context& ctx, const Frame& f, const std::vector<RangeRects>& rects) {
    glUseProgram(f.peak_program);
    aq::set_int(f.peak_program, "u_radius", f.reach_peak);
    const int axes[2][2] = {{1, 0}, {0, 1}};
    const aq_image sources[2] = {f.blur_intensity, f.horizontal};
    const aq_image targets[2] = {f.horizontal, f.peak};
    Rect RangeRects::*const which[2] = {&RangeRects::peak_rows, &RangeRects::paint};
    for (int pass = 0; pass < 2; ++pass) {
      aq::bind_texture(f.peak_program, "u_source", 0, sources[pass]);
      glUniform2i(glGetUniformLocation(f.peak_program, "u_axis"), axes[pass][0], axes[pass][1]);
      if (!each(rects, which[pass], [&] { return ctx.draw(targets[pass]); })) return false;
    }
    return true;
  }

  // Glaze the range over what lies under it, inside its layers' paint boxes (the last range:
  // everywhere, into the output).
  static bool composite_range(aq::Context& ctx, const Frame& f, size_t r,
                              const std::vector<RangeRects>& rects, std::vector<Rect>& last_paint) {
    const bool last = r + 1 == f.range_count;
    const aq_image& below = f.under[r % 2];
    const aq_image& target = last ? f.out : f.under[(r + 1) % 2];
    if (last) {
      glDisable(GL_SCISSOR_TEST);
    } else {
      // The ping-pong textures differ only where the previous range painted.
      for (const Rect& b : last_paint) {
        glCopyImageSubData(below.texture, GL_TEXTURE_2D, 0, b.x0, b.y0, 0, target.texture,
                           GL_TEXTURE_2D, 0, b.x0, b.y0, 0, b.x1 - b.x0 + 1, b.y1 - b.y0 + 1, 1);
      }
      last_paint.clear();
      for (const RangeRects& rr : rects) last_paint.push_back(rr.paint);
    }
    const GLuint p = f.composite;
    glUseProgram(p);
    aq::bind_texture(p, "u_under", 0, below);
    aq::bind_texture(p, "u_intensity", 1, f.intensity);
    aq::bind_texture(p, "u_diffuse", 2, f.diffuse);
    aq::bind_texture(p, "u_blur_intensity", 3, f.blur_intensity);
    aq::bind_texture(p, "u_blur_diffuse", 4, f.blur_diffuse);
    aq::bind_texture(p, "u_blur_depth", 5, f.blur_depth);
    aq::bind_texture(p, "u_blur_edges", 6, f.run_edges ? f.blur_edges : f.blur_intensity);
    aq::bind_texture(p, "u_depth", 7, ctx.input_image(3));
    if (f.has_paper) aq::bind_texture(p, "u_paper", 8, ctx.input_image(4));
    aq::bind_texture(p, "u_owner", 9, f.owner);
    aq::bind_texture(p, "u_table", 10, f.table);
    aq::bind_texture(p, "u_peak", 11, f.thin ? f.peak : f.blur_intensity);
    aq::set_float(p, "u_thin", f.thin ? ctx.param_float(kThinShapes) : 0.0);
    // A line one pixel wide blurred by σ peaks at 1/(√(2π)σ): its peak times √(2π)σ is its
    // width in pixels.
    aq::set_float(p, "u_line_width_scale", 2.5066283 * f.sigma);
    set_common(ctx, p);
    aq::set_vec2(p, "u_size", f.w, f.h);
    // A one-pixel edge band blurred by σ peaks near 2/(√(2π)σ): the gain brings it to ~1.
    const double gain = f.run_edges ? std::max(1.0, 1.2533 * f.edge_sigma) : 0.0;
    aq::set_float(p, "u_edge_gain", gain);
    aq::set_float(p, "u_edge_darkness", ctx.param_float(kEdgeDarkness));
    aq::set_float(p, "u_wet_spread", ctx.param_float(kWetSpread));
    aq::set_float(p, "u_edge_darkening", ctx.param_float(kEdgeDarkening));
    aq::set_float(p, "u_depth_band", ctx.param_float(kDepthBand));
    aq::set_float(p, "u_granulation", f.has_paper ? ctx.param_float(kGranulation) : 0.0);
    aq::set_float(p, "u_density", ctx.param_float(kDensity));
    aq::bind_texture(p, "u_colours", 12, f.colours);
    // The last range draws the whole image, where the owner image may still hold earlier
    // ranges' layers: the composite skips layers of other ranges.
    aq::set_float(p, "u_range", static_cast<double>(r));
    if (f.has_shadow) {
      aq::bind_texture(p, "u_shadow_layer", 13, f.shadow_blur);
      aq::bind_texture(p, "u_shadow_raw", 14, f.shadow_raw);
      aq::set_int(p, "u_last", last ? 1 : 0);
      aq::set_float(p, "u_shadows", ctx.param_float(kShadows));
      aq::set_vec3(p, "u_shadow_color", ctx.param_vec3(kShadowColor));
    }
    if (last) return ctx.draw(target);
    if (!ctx.bind_targets(&target, 1)) return false;
    return each(rects, &RangeRects::paint, [&] {
      ctx.raw()->host->draw_fullscreen(ctx.raw()->host_data);
      return true;
    });
  }

  // Soft shadows (README): the binary visibility and the smooth step over the gap behind the
  // occluder per receiver pixel (layered_shadow.frag), then the shared Gaussian of the
  // (shadow, receivers) pair; the last composite glazes it.
  // The shadow pass into f.shadow_raw, then its Gaussian of σ `sigma` (pixels of that image).
  bool shadow_layer(aq::Context& ctx, const Frame& f, double sigma) {
    const aq_scene* scene = ctx.input_scene(kScene);
    const aq_image shadow = ctx.input_image(kShadow);
    // The matrix the shadow map was drawn with (as cel_light finds it): fitted to the
    // receivers in view, for the map's size.
    const aq::scene_math::ViewFit fit = aq::scene_math::fit_to_view(
        *scene, mesh_boxes.world_boxes(*scene),
        static_cast<float>(ctx.width()) / static_cast<float>(ctx.height()));
    const glm::mat4 light = aq::scene_math::light_view_projection(*scene, fit, shadow.width);
    // Orthographic: window depth 0.5 · ndc_z + 0.5 grows by half the z row's length per unit.
    const double per_unit = 0.5 * glm::length(glm::dvec3(light[0][2], light[1][2], light[2][2]));
    glDisable(GL_SCISSOR_TEST);
    const GLuint p = f.shadow_program;
    glUseProgram(p);
    aq::bind_texture(p, "u_id", 0, ctx.input_image(kId));
    aq::bind_texture(p, "u_position", 1, ctx.input_image(kPosition));
    aq::bind_texture(p, "u_shadow", 2, shadow);
    aq::set_mat4(p, "u_light_view_projection", glm::value_ptr(light));
    aq::set_float(p, "u_depth_per_unit", per_unit);
    aq::set_float(p, "u_shadow_band", ctx.param_float(kShadowBand));
    if (!ctx.draw(f.shadow_raw)) return false;
    aq::unbind_textures(3);
    return aq::gaussian::blur_pass(ctx, f.shadow_raw, f.horizontal, sigma, 0) &&
           aq::gaussian::blur_pass(ctx, f.horizontal, f.shadow_blur, sigma, 1);
  }

  // The Gooch-mixed light and dark colour of every layer, once per frame (layered_colours).
  static bool gooch_colours(aq::Context& ctx, const Frame& f) {
    glDisable(GL_SCISSOR_TEST);
    glUseProgram(f.colours_program);
    aq::bind_texture(f.colours_program, "u_table", 0, f.table);
    set_gooch(ctx, f.colours_program);
    return ctx.draw(f.colours);
  }

  // Uniforms of layered_common.glsl.
  static void set_common(const aq::Context& ctx, GLuint program) {
    const double scale = ctx.render_scale();
    aq::set_float(program, "u_threshold", ctx.param_float(kThreshold));
    aq::set_float(program, "u_softness", ctx.param_float(kSoftness));
    aq::set_float(program, "u_edge_noise", ctx.param_float(kEdgeNoise));
    aq::set_float(program, "u_noise_scale", std::max(1e-3, ctx.param_float(kNoiseScale) * scale));
  }

  static void set_gooch(const aq::Context& ctx, GLuint program) {
    aq::set_float(program, "u_gooch", ctx.param_float(kGooch));
    aq::set_vec3(program, "u_warm", ctx.param_vec3(kWarm));
    aq::set_vec3(program, "u_cool", ctx.param_vec3(kCool));
  }
};

}  // namespace

AQ_NODE(kLayeredNode, Layered, "layered", "Watercolor",
        "Luft & Deussen's layered watercolor: a layer per object (segmentation), Blinn-Phong "
        "washes with paper-white highlights, Gaussian abstraction, wet-in-wet / wet-to-dry "
        "edges, edge darkening, granulation, pigment mixing and a blurred depth test, glazed far "
        "to near; soft shadows from a shadow map as a translucent layer.",
        0, kInputs, kOutputs, kParams);
AQ_PLUGIN("layered", "1.0", &kLayeredNode)
