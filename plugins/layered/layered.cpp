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

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "layer_table.h"
#include "layered_shaders.h"

namespace {

constexpr aq_port_desc kInputs[] = {
    aq::image_port("id", "object id per pixel (gbuffer.id, R32F); 0 on the background"),
    aq::image_port("normal", "world normal (gbuffer.normal)"),
    aq::image_port("albedo", "base colour (gbuffer.albedo): each object's mean is its pigment"),
    aq::image_port("depth", "linear view depth (gbuffer.depth); 0 on the background"),
    aq::optional_image_port("paper", "paper height in r (mean 0.5), e.g. the paper node"),
    aq::optional_scene_port("scene", "light and camera (else the light/view parameters)")};
constexpr aq_port_desc kOutputs[] = {aq::image_port("image", "the painting")};

enum Param {
  kMixing,
  kView,
  kLightDirection,
  kViewDirection,
  kShininess,
  kSpecularThreshold,
  kLightDensity,
  kDarkDensity,
  kPalette,
  kGooch,
  kWarm,
  kCool,
  kAbstractionSigma,
  kThreshold,
  kSoftness,
  kWetEdges,
  kWetInWetIds,
  kEdgeThreshold,
  kEdgeWidth,
  kEdgeDarkness,
  kWetSpread,
  kEdgeDarkening,
  kEdgeNoise,
  kNoiseScale,
  kGranulation,
  kPaperColor,
  kPaperRelief,
  kDepthBand,
  kDensity
};
enum WetEdges { kWetToDry = 0, kWetInWet = 1, kNoWetEdges = 2 };

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
    aq::float_param("gooch", 0.0, 0.0, 1.0,
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
    aq::float_param("density", 1.0, 0.0, 4.0, "pigment thickness of every wash")};

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
  std::string segment_text, edges_text, paper_text, composite_text;
  std::vector<float> id_pixels, depth_pixels, albedo_pixels;

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
    const aq_image id = ctx.input_image(0);
    const char* names[] = {"id", "normal", "albedo", "depth"};
    for (uint32_t i = 1; i < 4; ++i) {
      const aq_image other = ctx.input_image(i);
      if (other.width != id.width || other.height != id.height) {
        return ctx.fail(std::string("layered '") + ctx.node_id() + "': input '" + names[i] +
                        "' is " + std::to_string(other.width) + "x" + std::to_string(other.height) +
                        " but 'id' is " + std::to_string(id.width) + "x" +
                        std::to_string(id.height) +
                        ": connect the id, normal, albedo and depth of one gbuffer");
      }
    }

    // ---- The per-object table ----
    std::vector<layered::PaletteEntry> palette;
    std::vector<float> wet_ids;
    for (const auto& [param, error] :
         {std::pair{"palette", layered::parse_palette(ctx.param_string(kPalette), &palette)},
          std::pair{"wet_in_wet_ids",
                    layered::parse_id_list(ctx.param_string(kWetInWetIds), &wet_ids)}}) {
      if (!error.empty()) {
        return ctx.fail(std::string("layered '") + ctx.node_id() + "': parameter '" + param +
                        "': " + error);
      }
    }
    if (!read_back(id, GL_RED, 1, id_pixels) ||
        !read_back(ctx.input_image(3), GL_RED, 1, depth_pixels) ||
        !read_back(ctx.input_image(2), GL_RGBA, 4, albedo_pixels)) {
      return ctx.fail(std::string("layered '") + ctx.node_id() +
                      "': reading the id, depth and albedo inputs back failed: connect float "
                      "images (the gbuffer's id, depth and albedo outputs)");
    }
    std::vector<layered::Layer> layers = layered::collect_layers(
        id_pixels.data(), depth_pixels.data(), albedo_pixels.data(), id_pixels.size(), id.width);
    layered::ColourSettings colours;
    colours.light_density = ctx.param_float(kLightDensity);
    colours.dark_density = ctx.param_float(kDarkDensity);
    const int64_t wet_edges = ctx.param_enum(kWetEdges);
    colours.wet_in_wet_default = wet_edges == kWetInWet;
    layered::assign_colours(layers, colours, palette, wet_ids);

    // ---- Light and view ----
    double light[3], view[3];
    const aq_scene* scene = ctx.input_scene(5);
    const double* light_param = ctx.param_vec3(kLightDirection);
    const double* view_param = ctx.param_vec3(kViewDirection);
    for (int k = 0; k < 3; ++k) {
      light[k] = scene ? -static_cast<double>(scene->light.direction[k]) : -light_param[k];
      view[k] = scene ? static_cast<double>(scene->camera.position[k]) - scene->camera.target[k]
                      : view_param[k];
    }
    const double up[3] = {0.0, 1.0, 0.0}, towards_viewer[3] = {0.0, 0.0, 1.0};
    if (!finite3(light)) std::copy(up, up + 3, light);
    if (!finite3(view)) std::copy(towards_viewer, towards_viewer + 3, view);
    normalise(light, up);
    normalise(view, towards_viewer);
    double half[3] = {light[0] + view[0], light[1] + view[1], light[2] + view[2]};
    normalise(half, light);

    // ---- Textures: 11, whatever the number of objects ----
    const int w = id.width, h = id.height;
    const uint32_t f32 = AQ_FORMAT_RGBA32F;
    aq_image intensity, diffuse, depth, blur_intensity, blur_diffuse, blur_depth, edges, blur_edges,
        horizontal, under[2], out;
    const size_t range_count = (layers.size() + kLayersPerRange - 1) / kLayersPerRange;
    if (range_count > 0) {  // an empty frame is just the paper
      for (aq_image* t : {&intensity, &diffuse, &depth, &blur_intensity, &blur_diffuse, &blur_depth,
                          &edges, &blur_edges, &horizontal, &under[0], &under[1]}) {
        if (!ctx.scratch(w, h, f32, t)) return AQ_ERROR;
      }
    }
    if (!ctx.output_like(0, id, &out)) return AQ_ERROR;

    const bool has_paper = ctx.connected(4);
    const int64_t view_mode = ctx.param_enum(kView);
    const bool run_edges =
        (wet_edges != kNoWetEdges || !wet_ids.empty()) && (view_mode == 0 || view_mode == 4);
    const double scale = ctx.render_scale();
    const std::string defines = define("AQ_HAS_PAPER", has_paper ? 1 : 0) +
                                define("AQ_MIX_MODE", ctx.param_enum(kMixing)) +
                                define("AQ_VIEW", view_mode);
    segment_text = compose(defines, shaders::layered_segment_frag, "");
    edges_text =
        compose(defines, shaders::layered_edges_frag, "#include \"aquarelle/edge_kernels.glsl\"\n");
    paper_text = compose(defines, shaders::layered_paper_frag, "");
    composite_text =
        compose(defines, shaders::layered_composite_frag, "#include \"aquarelle/pigment.glsl\"\n");
    const GLuint segment = ctx.program({"layered_segment.frag", segment_text.c_str(), nullptr});
    const GLuint edge = ctx.program({"layered_edges.frag", edges_text.c_str(), nullptr});
    const GLuint paper = ctx.program({"layered_paper.frag", paper_text.c_str(), nullptr});
    const GLuint composite =
        ctx.program({"layered_composite.frag", composite_text.c_str(), nullptr});
    if (segment == 0 || edge == 0 || paper == 0 || composite == 0) return AQ_ERROR;

    bool ok = true;
    // The paper.
    glUseProgram(paper);
    if (has_paper) aq::bind_texture(paper, "u_paper", 0, ctx.input_image(4));
    aq::set_vec3(paper, "u_paper_color", ctx.param_vec3(kPaperColor));
    aq::set_float(paper, "u_paper_relief", ctx.param_float(kPaperRelief));
    aq::set_vec2(paper, "u_size", w, h);
    if (range_count == 0) {
      ok = ctx.draw(out);
    } else {
      ok = ctx.bind_targets(under, 2);
      if (ok) ctx.raw()->host->draw_fullscreen(ctx.raw()->host_data);
    }
    // The ping-pong textures agree everywhere but in the box the last range painted, which is
    // copied across before the next range paints its own box (so only the last composite
    // covers the whole image).
    Rect last_paint{0, 0, -1, -1};

    const double sigma = ctx.param_float(kAbstractionSigma) * scale;
    const double edge_sigma = ctx.param_float(kEdgeWidth) * scale;
    for (size_t r = 0; ok && r < range_count; ++r) {
      const size_t first = r * kLayersPerRange;
      const int count = static_cast<int>(std::min<size_t>(kLayersPerRange, layers.size() - first));
      float ids[4] = {-1.0f, -1.0f, -1.0f, -1.0f};
      float light_colors[12] = {}, dark_colors[12] = {}, wet[4] = {};
      for (int k = 0; k < count; ++k) {
        const layered::Layer& layer = layers[first + k];
        ids[k] = layer.id;
        for (int c = 0; c < 3; ++c) {
          light_colors[3 * k + c] = static_cast<float>(layer.light[c]);
          dark_colors[3 * k + c] = static_cast<float>(layer.dark[c]);
        }
        wet[k] = layer.wet_in_wet ? 1.0f : 0.0f;
      }
      // Where this range can paint: its objects' box grown by the abstraction's reach (R), and
      // the larger boxes each earlier pass must fill for the next one to read only what it
      // wrote this range (see README). Kernels wider than the image read its edge texels from
      // everywhere: then every pass covers the image.
      Rect box{w, h, -1, -1};
      for (int k = 0; k < count; ++k) {
        const layered::Layer& layer = layers[first + k];
        box = {std::min(box.x0, layer.x0), std::min(box.y0, layer.y0), std::max(box.x1, layer.x1),
               std::max(box.y1, layer.y1)};
      }
      const int reach_a = static_cast<int>(std::ceil(aq::gaussian::kTruncationSigmas * sigma)) + 1;
      const int reach_e =
          run_edges ? static_cast<int>(std::ceil(aq::gaussian::kTruncationSigmas * edge_sigma)) + 1
                    : 0;
      const bool whole = 2 * std::max(reach_a, reach_e) >= std::min(w, h) - 1;
      const Rect full{0, 0, w - 1, h - 1};
      const Rect paint = whole ? full : box.grown(reach_a, w, h);
      const Rect blurred = whole ? full : paint.grown(2 * reach_e + 1, w, h);
      const Rect blurred_rows = whole ? full : blurred.grown(reach_a, w, h);
      const Rect segmented = whole ? full : blurred_rows.grown(reach_a, w, h);
      const Rect edge_rect = whole ? full : paint.grown(2 * reach_e, w, h);
      const Rect edge_rows = whole ? full : paint.grown(reach_e, w, h);
      glEnable(GL_SCISSOR_TEST);

      // Segmentation and lighting, four objects at once.
      segmented.scissor();
      glUseProgram(segment);
      aq::bind_texture(segment, "u_id", 0, id);
      aq::bind_texture(segment, "u_normal", 1, ctx.input_image(1));
      aq::bind_texture(segment, "u_depth", 2, ctx.input_image(3));
      glUniform4fv(glGetUniformLocation(segment, "u_ids"), 1, ids);
      aq::set_vec3(segment, "u_light", light);
      aq::set_vec3(segment, "u_half", half);
      aq::set_float(segment, "u_shininess", ctx.param_float(kShininess));
      aq::set_float(segment, "u_specular_threshold", ctx.param_float(kSpecularThreshold));
      const aq_image targets[3] = {intensity, diffuse, depth};
      if (!ctx.bind_targets(targets, 3)) return fail_cleanly();
      ctx.raw()->host->draw_fullscreen(ctx.raw()->host_data);
      aq::unbind_textures(3);

      // Abstraction: the shared Gaussian.
      for (auto [in, blurred_out] :
           {std::pair{intensity, blur_intensity}, std::pair{diffuse, blur_diffuse},
            std::pair{depth, blur_depth}}) {
        blurred_rows.scissor();
        ok = ok && aq::gaussian::blur_pass(ctx, in, horizontal, sigma, 0);
        blurred.scissor();
        ok = ok && aq::gaussian::blur_pass(ctx, horizontal, blurred_out, sigma, 1);
      }
      if (!ok) break;

      // Wet edges: 3x3 Laplacian and threshold, widened by the Gaussian.
      if (run_edges) {
        glUseProgram(edge);
        aq::bind_texture(edge, "u_blurred", 0, blur_intensity);
        set_common(ctx, edge);
        aq::set_float(edge, "u_edge_threshold", ctx.param_float(kEdgeThreshold));
        edge_rect.scissor();
        ok = ctx.draw(edges);
        edge_rows.scissor();
        ok = ok && aq::gaussian::blur_pass(ctx, edges, horizontal, edge_sigma, 0);
        paint.scissor();
        ok = ok && aq::gaussian::blur_pass(ctx, horizontal, blur_edges, edge_sigma, 1);
        if (!ok) break;
      }

      // Glaze the range over what lies under it, inside `paint` (the last range: everywhere,
      // into the output).
      const bool last = r + 1 == range_count;
      const aq_image& below = under[r % 2];
      const aq_image& target = last ? out : under[(r + 1) % 2];
      if (last) {
        glDisable(GL_SCISSOR_TEST);
      } else {
        if (last_paint.x1 >= last_paint.x0) {
          glCopyImageSubData(below.texture, GL_TEXTURE_2D, 0, last_paint.x0, last_paint.y0, 0,
                             target.texture, GL_TEXTURE_2D, 0, last_paint.x0, last_paint.y0, 0,
                             last_paint.x1 - last_paint.x0 + 1, last_paint.y1 - last_paint.y0 + 1,
                             1);
        }
        paint.scissor();
        last_paint = paint;
      }
      glUseProgram(composite);
      aq::bind_texture(composite, "u_under", 0, below);
      aq::bind_texture(composite, "u_intensity", 1, intensity);
      aq::bind_texture(composite, "u_diffuse", 2, diffuse);
      aq::bind_texture(composite, "u_blur_intensity", 3, blur_intensity);
      aq::bind_texture(composite, "u_blur_diffuse", 4, blur_diffuse);
      aq::bind_texture(composite, "u_blur_depth", 5, blur_depth);
      aq::bind_texture(composite, "u_blur_edges", 6, run_edges ? blur_edges : blur_intensity);
      aq::bind_texture(composite, "u_depth", 7, ctx.input_image(3));
      if (has_paper) aq::bind_texture(composite, "u_paper", 8, ctx.input_image(4));
      set_common(ctx, composite);
      aq::set_vec2(composite, "u_size", w, h);
      aq::set_int(composite, "u_layer_count", count);
      glUniform4i(glGetUniformLocation(composite, "u_region"), paint.x0, paint.y0, paint.x1,
                  paint.y1);
      glUniform3fv(glGetUniformLocation(composite, "u_light_color"), 4, light_colors);
      glUniform3fv(glGetUniformLocation(composite, "u_dark_color"), 4, dark_colors);
      glUniform4fv(glGetUniformLocation(composite, "u_wet_in_wet"), 1, wet);
      // A one-pixel edge band blurred by σ peaks near 2/(√(2π)σ): the gain brings it to ~1.
      const double gain = run_edges ? std::max(1.0, 1.2533 * edge_sigma) : 0.0;
      aq::set_float(composite, "u_edge_gain", gain);
      aq::set_float(composite, "u_edge_darkness", ctx.param_float(kEdgeDarkness));
      aq::set_float(composite, "u_wet_spread", ctx.param_float(kWetSpread));
      aq::set_float(composite, "u_edge_darkening", ctx.param_float(kEdgeDarkening));
      aq::set_float(composite, "u_depth_band", ctx.param_float(kDepthBand));
      aq::set_float(composite, "u_granulation", has_paper ? ctx.param_float(kGranulation) : 0.0);
      aq::set_float(composite, "u_density", ctx.param_float(kDensity));
      set_gooch(ctx, composite);
      ok = ctx.draw(target);
    }
    glDisable(GL_SCISSOR_TEST);
    aq::unbind_textures(9);
    return ok ? AQ_OK : AQ_ERROR;
  }

  static int fail_cleanly() {
    glDisable(GL_SCISSOR_TEST);
    aq::unbind_textures(9);
    return AQ_ERROR;
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
        "to near.",
        0, kInputs, kOutputs, kParams);
AQ_PLUGIN("layered", "1.0", &kLayeredNode)
