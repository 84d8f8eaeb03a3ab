// The layered node's `fast` method: see fast_layers.h and README "Fast method".
//
//   id, depth, albedo ─► layered_table.comp ─► GPU table (hash of ids: count, sums)
//   table, palette ─► layered_fast_colours ─► per slot: Gooch light, dark, (depth, wet, id)
//   id, normal, depth ─► layered_fast_segment (½ size, 2x2 average) ─► lists: keys, I, D, Z
//   lists ─► Gaussian (horizontal, vertical; the lists grow to the 4 nearest layers)
//         ─► running max (thin shapes) and Laplacian edges ─► Gaussian of the edges
//   everything ─► layered_fast_composite (full size: bilinear per layer, glazes far to near)
#include "fast_layers.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "layered_params.h"
#include "layered_shaders.h"

namespace layered {

namespace {

constexpr int kTableWords = 12;  // per slot, as layered_table.comp lays them out

std::string define(const char* name, int64_t value) {
  return "#define " + std::string(name) + " " + std::to_string(value) + "\n";
}

// Variance (px² per axis) that the D×D average and the bilinear enlargement add by
// themselves: (D² − 1)/12 for the box, and for the enlargement the two-tap variance f (1 − f)
// texel² averaged over the D phases f of the output pixels (¾ px² at D = 2, 2.75 at D = 4).
double resampling_variance(int divisor) {
  double tent = 0.0;
  for (int k = 0; k < divisor; ++k) {
    const double u = (k + 0.5) / divisor - 0.5;
    const double f = u - std::floor(u);
    tent += f * (1.0 - f);
  }
  return (divisor * divisor - 1.0) / 12.0 + tent / divisor * divisor * divisor;
}

int radius_of(double sigma) {
  return sigma > 0.0 ? static_cast<int>(std::ceil(4.0 * sigma)) : 0;
}

// Normalised Gaussian weights by distance 0 … radius (the reference's 4σ truncation).
std::vector<float> gaussian_weights(double sigma, int radius) {
  std::vector<double> w(static_cast<size_t>(radius) + 1, 1.0);
  double sum = 1.0;
  for (int i = 1; i <= radius; ++i) {
    w[i] = std::exp(-static_cast<double>(i * i) / (2.0 * sigma * sigma));
    sum += 2.0 * w[i];
  }
  std::vector<float> out(w.size());
  for (size_t i = 0; i < w.size(); ++i) out[i] = static_cast<float>(w[i] / sum);
  return out;
}

// Kubelka–Munk absorption and scattering of the pigment whose unit layer reflects `rw` over
// white and 0.2 rw over black: aquarelle/pigment.glsl's aq_km_ks (maths in
// plugins/pigment_mix/README.md), for the shadow glaze's constant colour, once per frame.
void km_ks(double rw, double* k, double* s) {
  constexpr double kEps = 1.0e-4, kBlackRatio = 0.2;
  rw = std::isfinite(rw) ? std::clamp(rw, 0.0, 1.0) : 0.0;
  double rb = kBlackRatio * rw;
  rw = std::clamp(rw, 2.0 * kEps, 1.0 - kEps);
  rb = std::clamp(rb, kEps, rw - kEps);
  const double am1 = (1.0 - rw) * (1.0 - rb) / (2.0 * rb);
  const double b = std::sqrt(am1 * (am1 + 2.0));
  const double arg = std::max((1.0 - rb) * (1.0 + rw) / (2.0 * rb * b), 1.0 + 1.0e-6);
  *s = 0.5 * std::log((arg + 1.0) / (arg - 1.0)) / b;
  *k = am1 * *s;
}

GLuint compile_compute(aq::Context& ctx, const char* text) {
  const std::string source = std::string("#version 450 core\n") + text;
  const char* sources[] = {source.c_str()};
  const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  glShaderSource(shader, 1, sources, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  const GLuint program = glCreateProgram();
  if (ok) {
    glAttachShader(program, shader);
    glLinkProgram(program);
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
  }
  if (!ok) {
    char log[1024] = {0};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    ctx.fail(std::string("layered '") + ctx.node_id() + "': layered_table.comp did not compile: " +
             log + " (a compute shader needs OpenGL 4.3; use method 'exact')");
    glDeleteProgram(program);
    glDeleteShader(shader);
    return 0;
  }
  glDeleteShader(shader);
  return program;
}

}  // namespace

// Uniforms of layered_common.glsl.
void FastLayers::set_threshold(aq::Context& ctx, GLuint p) {
  aq::set_float(p, "u_threshold", ctx.param_float(kThreshold));
  aq::set_float(p, "u_softness", ctx.param_float(kSoftness));
  aq::set_float(p, "u_edge_noise", ctx.param_float(kEdgeNoise));
  aq::set_float(p, "u_noise_scale",
                std::max(1e-3, ctx.param_float(kNoiseScale) * ctx.render_scale()));
}

FastLayers::~FastLayers() {
  if (table_program_ != 0) glDeleteProgram(table_program_);
}

double FastLayers::low_sigma(double sigma, int divisor) {
  return std::sqrt(std::max(sigma * sigma - resampling_variance(divisor), 0.0)) / divisor;
}

int FastLayers::divisor_for(double sigma) {
  return sigma * sigma >= resampling_variance(4) + 1.0 ? 4 : 2;
}

bool FastLayers::applies(double sigma, double edge_sigma) {
  const int d = divisor_for(sigma);
  return sigma >= 1.5 && radius_of(low_sigma(sigma, d)) <= kMaxRadius &&
         radius_of(low_sigma(edge_sigma, d)) <= kMaxRadius;
}

std::string FastLayers::defines(aq::Context& ctx, const FastFrame& f) const {
  return define("AQ_DIVISOR", divisor_) + define("AQ_HAS_PAPER", f.has_paper ? 1 : 0) +
         define("AQ_HAS_SHADOW", f.has_shadow ? 1 : 0) +
         define("AQ_MIX_MODE", ctx.param_enum(kMixing)) + define("AQ_VIEW", 0);
}

GLuint FastLayers::fragment(aq::Context& ctx, const char* name, std::string& text,
                            const aq_shader_source& main, const std::string& defines) {
  text = defines +
         "#include \"aquarelle/pigment.glsl\"\n#include \"aquarelle/edge_kernels.glsl\"\n" +
         shaders::layered_common_glsl.text + "\n" + shaders::layered_lists_glsl.text +
         "\n#line 1\n" + main.text;
  return ctx.program({name, text.c_str(), nullptr});
}

bool FastLayers::run(aq::Context& ctx, const FastFrame& f) {
  if (table_program_ == 0 || generation_ != ctx.raw()->gl_generation) {
    if (generation_ != ctx.raw()->gl_generation) {
      table_.forget();
      bilinear_.forget();
    }
    table_program_ = compile_compute(ctx, shaders::layered_table_comp.text);
    generation_ = ctx.raw()->gl_generation;
    if (table_program_ == 0) return false;
  }
  Targets t;
  // Forgotten unless this run reaches the kept texture (threshold_map).
  const std::array<double, 5> drawn_with = threshold_key_;
  forget_kept();
  divisor_ = divisor_for(f.sigma);
  const int hw = (f.w + divisor_ - 1) / divisor_, hh = (f.h + divisor_ - 1) / divisor_;
  const uint32_t f32 = AQ_FORMAT_RGBA32F;
  if (!ctx.scratch(f.w, f.h, f32, &t.pixels)) return false;
  for (aq_image* image :
       {&t.lists[0], &t.lists[1], &t.lists[2], &t.lists[3], &t.spare[0], &t.spare[1], &t.spare[2],
        &t.spare[3], &t.peak, &t.spare_one, &t.edges, &t.blur_edges}) {
    if (!ctx.scratch(hw, hh, f32, image)) return false;
  }
  glDisable(GL_SCISSOR_TEST);
  static const bool profile = std::getenv("AQ_LAYERED_PROFILE") != nullptr;
  auto clock = std::chrono::steady_clock::now();
  auto lap = [&](const char* what) {
    if (!profile) return true;
    glFinish();
    const auto now = std::chrono::steady_clock::now();
    std::fprintf(stderr, "layered fast %s %.1f ms\n", what,
                 std::chrono::duration<double, std::milli>(now - clock).count());
    clock = now;
    return true;
  };
  lap("before");
  const bool ok = build_table(ctx) && lap("table") && colours(ctx, f, t) && lap("colours") &&
                  segment_and_blur(ctx, f, t) && lap("segment+blur") &&
                  peaks_and_edges(ctx, f, t) && lap("peaks+edges") && cells(ctx, f, t) &&
                  lap("cells") && threshold_map(ctx, f, t, drawn_with) && lap("threshold") &&
                  composite(ctx, f, t) && lap("composite");
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
  aq::unbind_textures(16);
  return ok;
}

// The GPU table: cleared, then one invocation per run of 64 pixels of a row.
bool FastLayers::build_table(aq::Context& ctx) {
  const GLsizeiptr bytes = static_cast<GLsizeiptr>(kSlots) * kTableWords * sizeof(uint32_t);
  if (!table_) glNamedBufferStorage(table_.create(), bytes, nullptr, GL_DYNAMIC_STORAGE_BIT);
  const uint32_t zero = 0;
  glClearNamedBufferData(table_.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, table_.get());
  glUseProgram(table_program_);
  aq::bind_texture(table_program_, "u_id", 0, ctx.input_image(kId));
  aq::bind_texture(table_program_, "u_depth", 1, ctx.input_image(kDepth));
  aq::bind_texture(table_program_, "u_albedo", 2, ctx.input_image(kAlbedo));
  aq::set_int(table_program_, "u_slots", kSlots);
  const aq_image id = ctx.input_image(kId);
  const GLuint runs = static_cast<GLuint>(id.height) * ((id.width + 63) / 64);
  glDispatchCompute((runs + 63) / 64, 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  return true;
}

// Per slot: Gooch light and dark colours (or their K and S), mean depth, id and wet-in-wet.
bool FastLayers::colours(aq::Context& ctx, const FastFrame& f, Targets& t) {
  const int n = std::max<int>(1, static_cast<int>(f.palette.size() + f.wet_ids.size()));
  if (!ctx.scratch(kSlots, 4, AQ_FORMAT_RGBA32F, &t.colours) ||
      !ctx.scratch(n, 3, AQ_FORMAT_RGBA32F, &t.overrides)) {
    return false;
  }
  overrides_.assign(static_cast<size_t>(n) * 3 * 4, 0.0f);
  int i = 0;
  for (const PaletteEntry& e : f.palette) {
    float* head = &overrides_[4 * i];
    head[0] = e.id;
    head[2] = e.has_dark ? 1.0f : 0.0f;
    for (int c = 0; c < 3; ++c) {
      overrides_[4 * (n + i) + c] = static_cast<float>(e.light[c]);
      overrides_[4 * (2 * n + i) + c] = static_cast<float>(e.dark[c]);
    }
    ++i;
  }
  for (float id : f.wet_ids) {
    overrides_[4 * i] = id;
    overrides_[4 * i + 1] = 1.0f;
    ++i;
  }
  glTextureSubImage2D(t.overrides.texture, 0, 0, 0, n, 3, GL_RGBA, GL_FLOAT, overrides_.data());
  const GLuint p = fragment(ctx, "layered_fast_colours.frag", colours_text_,
                            shaders::layered_fast_colours_frag, defines(ctx, f));
  if (p == 0) return false;
  glUseProgram(p);
  aq::bind_texture(p, "u_overrides", 0, t.overrides);
  aq::set_int(p, "u_override_count", i);
  aq::set_int(p, "u_wet_default", f.wet_default ? 1 : 0);
  aq::set_float(p, "u_light_density", ctx.param_float(kLightDensity));
  aq::set_float(p, "u_dark_density", ctx.param_float(kDarkDensity));
  aq::set_float(p, "u_gooch", ctx.param_float(kGooch));
  aq::set_vec3(p, "u_warm", ctx.param_vec3(kWarm));
  aq::set_vec3(p, "u_cool", ctx.param_vec3(kCool));
  return ctx.draw(t.colours);
}

// Half-resolution lists (keys, I, D, Z), then their Gaussian, horizontal then vertical: the
// result is back in t.lists.
bool FastLayers::segment_and_blur(aq::Context& ctx, const FastFrame& f, Targets& t) {
  const GLuint p = fragment(ctx, "layered_fast_segment.frag", segment_text_,
                            shaders::layered_fast_segment_frag, defines(ctx, f));
  if (p == 0) return false;
  glUseProgram(p);
  aq::bind_texture(p, "u_id", 0, ctx.input_image(kId));
  aq::bind_texture(p, "u_normal", 1, ctx.input_image(kNormal));
  aq::bind_texture(p, "u_depth", 2, ctx.input_image(kDepth));
  aq::set_vec3(p, "u_light", f.light);
  aq::set_vec3(p, "u_half", f.half);
  aq::set_float(p, "u_shininess", ctx.param_float(kShininess));
  aq::set_float(p, "u_specular_threshold", ctx.param_float(kSpecularThreshold));
  aq::set_int(p, "u_slots", kSlots);
  aq::set_int(p, "u_pixels", 0);
  glBindImageTexture(0, t.pixels.texture, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  if (!ctx.bind_targets(t.lists, 4)) return false;
  ctx.raw()->host->draw_fullscreen(ctx.raw()->host_data);
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  const double sigma = low_sigma(f.sigma, divisor_);
  const int radius = radius_of(sigma);
  return gather(ctx, 0, t.lists[0], &t.lists[1], 0, sigma, radius, t.spare, 4) &&
         gather(ctx, 0, t.spare[0], &t.spare[1], 1, sigma, radius, t.lists, 4);
}

// Thin shapes' running maximum (radius ⌈σ⌉ + 1 px, halved) and the wet edges with their
// Gaussian, all on the blurred lists' keys.
bool FastLayers::peaks_and_edges(aq::Context& ctx, const FastFrame& f, Targets& t) {
  if (f.thin) {
    const int r = (static_cast<int>(std::ceil(f.sigma)) + 1 + divisor_ - 1) / divisor_;
    if (!gather(ctx, 2, t.lists[0], &t.lists[1], 0, 0.0, r, &t.spare_one, 1) ||
        !gather(ctx, 2, t.lists[0], &t.spare_one, 1, 0.0, r, &t.peak, 1)) {
      return false;
    }
  }
  if (!f.run_edges) return true;
  const GLuint p = fragment(ctx, "layered_fast_edges.frag", edges_text_,
                            shaders::layered_fast_edges_frag, defines(ctx, f));
  if (p == 0) return false;
  glUseProgram(p);
  aq::bind_texture(p, "u_keys", 0, t.lists[0]);
  aq::bind_texture(p, "u_blurred", 1, t.lists[1]);
  aq::set_float(p, "u_edge_threshold", ctx.param_float(kEdgeThreshold));
  set_threshold(ctx, p);
  if (!ctx.draw(t.edges)) return false;
  const double sigma = low_sigma(f.edge_sigma, divisor_);
  const int radius = radius_of(sigma);
  return gather(ctx, 1, t.lists[0], &t.edges, 0, sigma, radius, &t.spare_one, 1) &&
         gather(ctx, 1, t.lists[0], &t.spare_one, 1, sigma, radius, &t.blur_edges, 1);
}

// One axis of layered_fast_gather.frag: mode 0 grows the lists (keys and I, D, Z in
// `values[0..2]`), 1 blurs and 2 takes the maximum of one value per key of a fixed list.
bool FastLayers::gather(aq::Context& ctx, int mode, const aq_image& keys, const aq_image* values,
                        int axis, double sigma, int radius, const aq_image* targets,
                        int target_count) {
  // Small radii compiled in (layered_fast_gather.frag); a few programs per graph.
  const std::string defs =
      define("AQ_GATHER", mode) + (radius <= kUnrolledRadius ? define("AQ_RADIUS", radius) : "");
  const GLuint p = fragment(ctx, "layered_fast_gather.frag", gather_text_[mode],
                            shaders::layered_fast_gather_frag, defs);
  if (p == 0) return false;
  glUseProgram(p);
  aq::bind_texture(p, "u_keys", 0, keys);
  if (mode == 0) {
    aq::bind_texture(p, "u_intensity", 1, values[0]);
    aq::bind_texture(p, "u_diffuse", 2, values[1]);
    aq::bind_texture(p, "u_depth", 3, values[2]);
  } else {
    aq::bind_texture(p, "u_values", 1, values[0]);
  }
  glUniform2i(glGetUniformLocation(p, "u_axis"), axis == 0 ? 1 : 0, axis == 0 ? 0 : 1);
  if (radius > kUnrolledRadius) aq::set_int(p, "u_radius", radius);
  if (mode != 2) {
    const std::vector<float> w = gaussian_weights(sigma, radius);
    glUniform1fv(glGetUniformLocation(p, "u_weights"), static_cast<GLsizei>(w.size()), w.data());
  }
  if (!ctx.bind_targets(targets, static_cast<uint32_t>(target_count))) return false;
  ctx.raw()->host->draw_fullscreen(ctx.raw()->host_data);
  return true;
}

// Per pixel (layered_threshold, paper height h) in one kept texture, drawn again only when the
// size, the context, the threshold's parameters or the paper change (the noise depends on
// nothing else): the composite reads one texel for both.
bool FastLayers::threshold_map(aq::Context& ctx, const FastFrame& f, Targets& t,
                               const std::array<double, 5>& drawn_with) {
  const std::array<double, 5> key = {
      ctx.param_float(kThreshold), ctx.param_float(kEdgeNoise),
      std::max(1e-3, ctx.param_float(kNoiseScale) * ctx.render_scale()), ctx.param_float(kSoftness),
      f.has_paper ? 1.0 : 0.0};
  bool kept = false;
  t.threshold = {threshold_.get(ctx.raw()->gl_generation, f.w, f.h, GL_RGBA32F, &kept), f.w, f.h,
                 AQ_FORMAT_RGBA32F};
  const bool paper_changed = f.has_paper && !ctx.input_damage(kPaper).empty();
  if (kept && key == drawn_with && !paper_changed) {
    threshold_key_ = key;
    return true;
  }
  const GLuint p = fragment(ctx, "layered_fast_threshold.frag", threshold_text_,
                            shaders::layered_fast_threshold_frag, defines(ctx, f));
  if (p == 0) return false;
  glUseProgram(p);
  set_threshold(ctx, p);
  if (f.has_paper) aq::bind_texture(p, "u_paper", 0, ctx.input_image(kPaper));
  aq::set_vec2(p, "u_size", f.w, f.h);
  if (!ctx.draw(t.threshold)) return false;
  threshold_key_ = key;
  return true;
}

// The cells' merged, ordered lists, then their 2 x 2 blocks of re-keyed corner values
// (layered_fast_cells.frag, layered_fast_blocks.frag): (W + 1) x (H + 1) cells of the lists.
bool FastLayers::cells(aq::Context& ctx, const FastFrame& f, Targets& t) {
  const GLuint p = fragment(ctx, "layered_fast_cells.frag", cells_text_,
                            shaders::layered_fast_cells_frag, defines(ctx, f));
  const GLuint b = fragment(ctx, "layered_fast_blocks.frag", blocks_text_,
                            shaders::layered_fast_blocks_frag, defines(ctx, f));
  if (p == 0 || b == 0) return false;
  // The targets first: a texture made after the inputs are bound could unbind one of them.
  const int cw = t.lists[0].width + 1, ch = t.lists[0].height + 1;
  if (!ctx.scratch(cw, ch, AQ_FORMAT_RGBA32F, &t.cells)) return false;
  for (aq_image& block : t.blocks) {
    if (!ctx.scratch(2 * cw, 2 * ch, AQ_FORMAT_RGBA32F, &block)) return false;
  }
  glUseProgram(p);
  aq::bind_texture(p, "u_keys", 0, t.lists[0]);
  aq::bind_texture(p, "u_colours", 1, t.colours);
  if (!ctx.draw(t.cells)) return false;
  glUseProgram(b);
  aq::bind_texture(b, "u_cells", 0, t.cells);
  aq::bind_texture(b, "u_keys", 1, t.lists[0]);
  aq::bind_texture(b, "u_blur_intensity", 2, t.lists[1]);
  aq::bind_texture(b, "u_blur_diffuse", 3, t.lists[2]);
  aq::bind_texture(b, "u_blur_depth", 4, t.lists[3]);
  aq::bind_texture(b, "u_blur_edges", 5, f.run_edges ? t.blur_edges : t.lists[1]);
  aq::bind_texture(b, "u_peak", 6, f.thin ? t.peak : t.lists[1]);
  if (!ctx.bind_targets(t.blocks, 5)) return false;
  ctx.raw()->host->draw_fullscreen(ctx.raw()->host_data);
  return true;
}

// The composite in four draws, one per class of pixels by the last layer their cell lists (0 to
// 2, and 3 or 4 together): the classes pass writes the class into a depth buffer, and each draw,
// compiled for its number of layers, is let in by the depth test EQUAL at its class's depth (the
// depth range [d, d] puts the full-screen triangle there). llvmpipe tests depth before the shader
// and skips the groups of pixels that all fail, so a pixel pays for the layers its cell may list,
// not for four (a loop per layer did not: llvmpipe ran it for every pixel).
bool FastLayers::composite(aq::Context& ctx, const FastFrame& f, const Targets& t) {
  const GLuint classes = fragment(ctx, "layered_fast_classes.frag", classes_text_,
                                  shaders::layered_fast_classes_frag, defines(ctx, f));
  if (classes == 0) return false;
  bool kept = false;
  const aq_image depth = class_depth_.get(ctx.raw()->gl_generation, f.w, f.h, &kept);
  glUseProgram(classes);
  aq::bind_texture(classes, "u_cells", 0, t.cells);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_ALWAYS);
  bool ok = ctx.bind_targets(&f.out, 1, &depth);
  if (ok) ctx.raw()->host->draw_fullscreen(ctx.raw()->host_data);
  glDepthMask(GL_FALSE);
  glDepthFunc(GL_EQUAL);
  for (int layer_class = 0; layer_class <= 3 && ok; ++layer_class) {
    const double class_depth = (layer_class + 1) / 8.0;
    const int layers = layer_class == 3 ? 4 : layer_class;
    const GLuint p = fragment(ctx, "layered_fast_composite.frag", composite_texts_[layer_class],
                              shaders::layered_fast_composite_frag,
                              defines(ctx, f) + define("AQ_LAYER_COUNT", layers));
    ok = p != 0 && set_composite_inputs(ctx, f, t, p) && ctx.bind_targets(&f.out, 1, &depth);
    if (!ok) break;
    glDepthRange(class_depth, class_depth);
    ctx.raw()->host->draw_fullscreen(ctx.raw()->host_data);
  }
  glDepthRange(0.0, 1.0);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_DEPTH_TEST);
  for (GLuint unit = 1; unit <= 13; ++unit) glBindSampler(unit, 0);
  return ok;
}

// The composite program's textures, samplers and uniforms.
bool FastLayers::set_composite_inputs(aq::Context& ctx, const FastFrame& f, const Targets& t,
                                      GLuint p) {
  glUseProgram(p);
  aq::bind_texture(p, "u_cells", 0, t.cells);
  const char* blocks[] = {"u_slot0", "u_slot1", "u_slot2", "u_slot3", "u_block_peak"};
  for (GLuint i = 0; i < 5; ++i) aq::bind_texture(p, blocks[i], 1 + i, t.blocks[i]);
  aq::bind_texture(p, "u_pixels", 6, t.pixels);
  aq::bind_texture(p, "u_colours", 10, t.colours);
  if (!bilinear_) {
    const GLuint s = bilinear_.create();
    glSamplerParameteri(s, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glSamplerParameteri(s, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glSamplerParameteri(s, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(s, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  for (GLuint unit : {1u, 2u, 3u, 4u, 5u}) glBindSampler(unit, bilinear_.get());
  if (f.has_shadow) {
    aq::bind_texture(p, "u_shadow_layer", 11, f.shadow_blur);
    glBindSampler(11, bilinear_.get());
    aq::set_float(p, "u_shadows", ctx.param_float(kShadows));
    const double* colour = ctx.param_vec3(kShadowColor);
    double k[3], sc[3];
    for (int c = 0; c < 3; ++c) km_ks(colour[c], &k[c], &sc[c]);
    aq::set_vec3(p, "u_shadow_k", k);
    aq::set_vec3(p, "u_shadow_s", sc);
  }
  aq::bind_texture(p, "u_threshold_map", 12, t.threshold);
  set_threshold(ctx, p);
  aq::set_vec2(p, "u_size", f.w, f.h);
  aq::set_float(p, "u_thin", f.thin ? ctx.param_float(kThinShapes) : 0.0);
  // b / m is 1 on a thin shape's ridge at full size; interpolated from texels four pixels apart
  // it dips between them, so the quarter resolution takes a lower step (a wide shape's
  // rounded corner stays near 0.3 and is still dropped).
  if (divisor_ == 4) {
    aq::set_vec2(p, "u_ridge", 0.45, 0.65);
  } else {
    aq::set_vec2(p, "u_ridge", 0.75, 0.9);
  }
  aq::set_float(p, "u_line_width_scale", 2.5066283 * f.sigma);
  aq::set_float(p, "u_edge_gain", f.run_edges ? std::max(1.0, 1.2533 * f.edge_sigma) : 0.0);
  aq::set_float(p, "u_edge_darkness", ctx.param_float(kEdgeDarkness));
  aq::set_float(p, "u_wet_spread", ctx.param_float(kWetSpread));
  aq::set_float(p, "u_edge_darkening", ctx.param_float(kEdgeDarkening));
  aq::set_float(p, "u_depth_band", ctx.param_float(kDepthBand));
  aq::set_float(p, "u_granulation", f.has_paper ? ctx.param_float(kGranulation) : 0.0);
  aq::set_float(p, "u_density", ctx.param_float(kDensity));
  aq::set_vec3(p, "u_paper_color", ctx.param_vec3(kPaperColor));
  aq::set_float(p, "u_paper_relief", ctx.param_float(kPaperRelief));
  return true;
}

}  // namespace layered
