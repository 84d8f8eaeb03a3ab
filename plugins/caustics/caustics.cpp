// caustics: a tileable, animated caustic texture by Stam's grid refraction ("Periodic Caustic
// Textures", 2004), as the seed (Paré-Vogt & Chaid §4) uses it, with its physical mistakes
// fixed: periodic water, analytic normals, light conserved through folds and wrap-around
// instead of a 1.2x oversized grid. See README.md.
//
//   displacement (one fragment per grid vertex: water, Snell, where the ray meets the floor)
//     ├─ coverage (default): each refracted triangle's light shared among the texels by exact
//     │    area of overlap, integer atomics -> counts; counts minus flat water's -> intensity
//     └─ point (Stam's): refracted triangles rasterised at texel centres with intensity
//          original / refracted area, additive blend; optional read-back normalisation
#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/gl_raii.hpp>
#include <aquarelle/sdk/scene_math.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "caustics_shaders.h"

namespace {

constexpr aq_port_desc kInputs[] = {aq::optional_scene_port(
    "scene", "the scene the caustics fall on: sizes the texture to its footprint on screen")};
constexpr aq_port_desc kOutputs[] = {
    aq::image_port("image", "caustic intensity in rgb (1 = unfocused light), tileable")};
enum Param {
  kResolution,
  kGrid,
  kDepth,
  kAmplitude,
  kWaveScale,
  kSpeed,
  kEta,
  kMaxIntensity,
  kNormalizeEnergy,
  kAutoResolution,
  kEstimator,
  kAutoGrid,
  kWindow,
  kBlendCount,
  kBlendInterval,
  kShift
};
enum Estimator { kCoverage, kPoint };
constexpr aq_param_desc kParams[] = {
    aq::int_param("resolution", 256, 1, 4096,
                  "texture pixels per tile side (square output; the largest, with "
                  "auto_resolution)"),
    aq::int_param("grid", 256, 4, 2048,
                  "refraction grid cells per tile side; error falls as 1/grid (see README)"),
    aq::float_param("depth", 0.5, 0.0, 4.0, "floor depth below the mean water level, in tiles"),
    aq::float_param("amplitude", 0.02, 0.0, 0.25, "water height amplitude, in tiles"),
    aq::int_param("wave_scale", 4, 1, 64, "waves (noise cells) per tile of the first octave"),
    aq::float_param("speed", 0.5, 0.0, 10.0, "noise cells per second along the time axis"),
    aq::float_param("eta", 1.0 / 1.333, 0.1, 1.0,
                    "refraction ratio n_air / n_water (1 = no refraction)"),
    aq::float_param("max_intensity", 32.0, 1.0, 10000.0,
                    "estimator point: clamp of one triangle's intensity (bounds degenerate "
                    "triangles)",
                    0.0, "log"),
    aq::bool_param("normalize_energy", true,
                   "estimator point: rescale so the tile's mean is exactly 1 (corrects clamp and "
                   "sampling loss; coverage conserves the light by construction)"),
    aq::bool_param("auto_resolution", true,
                   "with `scene` connected: about one texel per screen pixel at the nearest "
                   "receiver in view under the water (at most `resolution`)"),
    aq::enum_param("estimator", "coverage|point", kCoverage,
                   "coverage: each refracted triangle's light shared among texels by exact area "
                   "of overlap (box filter, converges as 1/grid^2); point: Stam's triangles "
                   "sampled at texel centres (see README)"),
    aq::bool_param("auto_grid", false,
                   "at final quality with auto_resolution: at most a grid cell per two texels "
                   "of the texture (the proxy presets' density): about a quarter of the cost, "
                   "1.5 dB less pipeline PSNR on the underwater graph; off: the grid asked for"),
    aq::int_param("window", 3, 2, 3,
                  "estimator coverage: texels per side of the window whose overlaps are shared "
                  "in closed form (larger triangles go texel by texel, a loop every SIMD lane "
                  "runs); 3 costs a quarter to a third less than 2 on llvmpipe, with the same "
                  "light per tile (a few texels split differently in float, see README)"),
    aq::int_param("blend_count", 1, 1, 5,
                  "caustic images at successive times mixed into one (seed 001's murky water: "
                  "5, weights .4 .3 .2 .1 .05 normalised to sum 1, so the mean stays 1); each "
                  "costs a whole texture"),
    aq::float_param("blend_interval", 0.25, 0.0, 10.0,
                    "seconds between the blended images (image k is at time t - k * interval)"),
    aq::color_param("shift", 0.0, 0.0, 0.0,
                    "added to the intensity per channel (seed 001's blue shift: 0, 0.05, 0.1); "
                    "light multiplied by it turns bluer in the light and in the shade")};

// The seed's weights for the blended caustic images, newest first (Coleman & Dodson).
constexpr double kBlendWeights[5] = {0.4, 0.3, 0.2, 0.1, 0.05};

// Texture pixels per tile side for about one texel per screen pixel where the tile is seen
// largest: at the nearest point, under the water, of the meshes' boxes in view, where a tile is
// `tile` world units wide (the scene's caustic_tile, as cel_light projects it).
int footprint_resolution(const aq_scene& scene, aq::view_bounds::MeshBoxes& boxes, double tile,
                         int width, int height, int largest) {
  const aq::view_bounds::Plane under_water[] = {aq::view_bounds::below(scene.water_height)};
  const auto points = aq::scene_math::visible_receivers(
      scene, boxes.world_boxes(scene), static_cast<float>(width) / static_cast<float>(height),
      under_water);
  const auto depth = aq::scene_math::nearest_receiver_depth(scene.camera, points);
  if (!depth) return std::min(largest, 16);  // no receiver in view: nothing to show
  return aq::scene_math::footprint_texels(tile, scene.camera, height, *depth, 8, largest);
}

// A run of grid cells along one axis: [first, first + count).
struct CellRange {
  int first = 0;
  int count = 0;
};

// The cells of a copy shifted by `shift` tiles whose refracted triangles can reach the tile
// [0, grid] along one axis: the cell [c, c + 1] moved by shift * grid and by at most `reach`
// cells must overlap it. One cell of margin on each side keeps rounding harmless.
CellRange cells_reaching_tile(int shift, int grid, double reach) {
  const double offset = double(shift) * grid;
  const int first = std::max(0, static_cast<int>(std::floor(-offset - reach - 1.0)) - 1);
  const int last = std::min(grid - 1, static_cast<int>(std::ceil(grid - offset + reach)) + 1);
  return {first, last - first + 1};
}

struct Caustics {
  aq::gl::VertexArray empty_vertex_array;  // core profile needs one bound to draw
  aq::view_bounds::MeshBoxes boxes;
  uint32_t vertex_array_generation = 0;

  int process(aq::Context& ctx) {
    // `resolution` is for a full-size render; a proxy render shows the tile on fewer pixels.
    int resolution =
        std::max(1, static_cast<int>(std::lround(static_cast<double>(ctx.param_int(kResolution)) *
                                                 ctx.render_scale())));
    const aq_scene* scene = ctx.input_scene(0);
    if (scene != nullptr && ctx.param_bool(kAutoResolution)) {
      resolution = footprint_resolution(*scene, boxes, aq::scene_caustic_tile(*scene), ctx.width(),
                                        ctx.height(), resolution);
    }
    // The quality preset trades the grid for speed. Coverage's error is set by the grid against
    // the waves more than by the texture (default waves, grid 192: 38 dB at 64 texels, 33 at
    // 128, 28 at 256; grid 128 at 128 texels: 26 dB), so draft keeps a half and preview three
    // quarters while the texture shrinks with the render scale. Point sampling (cost ~ grid^2
    // rasterised triangles, error ~ 1/grid): draft an eighth, preview a quarter.
    const bool point = ctx.param_enum(kEstimator) == kPoint;
    const int quality = static_cast<int>(ctx.quality());
    const int grid_asked = static_cast<int>(ctx.param_int(kGrid));
    int grid = std::max(4, quality >= 2 ? grid_asked
                           : point      ? grid_asked / (quality == 0 ? 8 : 4)
                                        : grid_asked * (quality == 0 ? 2 : 3) / 4);
    // With `auto_grid` and `auto_resolution` at final: no finer than a cell per two texels of the
    // footprint's texture (off by default: measured with the point estimator it cost 1.5 dB of
    // pipeline PSNR, see README).
    if (quality >= 2 && scene != nullptr && ctx.param_bool(kAutoResolution) &&
        ctx.param_bool(kAutoGrid)) {
      grid = std::min(grid, std::max(4, (resolution + 1) / 2));
    }
    const double eta = ctx.param_float(kEta);
    if (resolution < 1 || grid < 1) {
      return ctx.fail("caustics: resolution and grid must be at least 1 (got resolution " +
                      std::to_string(resolution) + ", grid " + std::to_string(grid) + ")");
    }
    if (!(eta > 0.0 && eta <= 1.0)) {
      return ctx.fail("caustics: eta must be in (0, 1] (light enters water from air); got " +
                      std::to_string(eta));
    }

    aq_image displacement, out;
    if (!ctx.scratch(grid, grid, AQ_FORMAT_RGBA32F, &displacement)) return AQ_ERROR;
    if (!ctx.output(0, resolution, resolution, ctx.working_format(), &out)) return AQ_ERROR;
    const int count = static_cast<int>(ctx.param_int(kBlendCount));
    const double* shift = ctx.param_vec3(kShift);
    if (count <= 1 && shift[0] == 0.0 && shift[1] == 0.0 && shift[2] == 0.0) {
      return estimate(ctx, displacement, out, grid, ctx.time()) ? AQ_OK : AQ_ERROR;
    }
    // Blended or shifted: each image into a float scratch, then one pass mixes them.
    aq_image images[5];
    for (int k = 0; k < count; ++k) {
      const double time = ctx.time() - k * ctx.param_float(kBlendInterval);
      if (!ctx.scratch(resolution, resolution, AQ_FORMAT_RGBA32F, &images[k])) return AQ_ERROR;
      if (!estimate(ctx, displacement, images[k], grid, time)) return AQ_ERROR;
    }
    return blend(ctx, images, count, shift, out) ? AQ_OK : AQ_ERROR;
  }

 private:
  // One caustic image at `time` into `out`: the refracted grid, then the chosen estimator.
  bool estimate(aq::Context& ctx, const aq_image& displacement, const aq_image& out, int grid,
                double time) {
    const double depth = ctx.param_float(kDepth);
    const double amplitude = ctx.param_float(kAmplitude);
    if (!refract_grid(ctx, displacement, grid, depth, amplitude, ctx.param_float(kEta), time)) {
      return false;
    }
    if (ctx.param_enum(kEstimator) == kPoint) {
      return point_estimate(ctx, displacement, out, grid, depth, amplitude);
    }
    return coverage_estimate(ctx, displacement, out, grid);
  }

  // out = Σ_k w_k image_k / Σ_k w_k + shift, w the seed's weights for the first `count`.
  static bool blend(aq::Context& ctx, const aq_image* images, int count, const double* shift,
                    const aq_image& out) {
    GLuint program = ctx.program(shaders::caustics_blend_frag);
    if (program == 0) return false;
    glUseProgram(program);
    double total = 0.0;
    for (int k = 0; k < count; ++k) total += kBlendWeights[k];
    for (int k = 0; k < 5; ++k) {
      const std::string at = "[" + std::to_string(k) + "]";
      aq::bind_texture(program, ("u_images" + at).c_str(), k, images[k < count ? k : 0]);
      aq::set_float(program, ("u_weights" + at).c_str(),
                    k < count ? kBlendWeights[k] / total : 0.0);
    }
    aq::set_vec3(program, "u_shift", shift);
    const bool drawn = ctx.draw(out);
    aq::unbind_textures(5);
    return drawn;
  }

  // Stam's estimator: refracted triangles rasterised at texel centres (see README).
  bool point_estimate(aq::Context& ctx, const aq_image& displacement, const aq_image& out, int grid,
                      double depth, double amplitude) {
    aq_image accumulated;
    if (!ctx.scratch(out.width, out.height, AQ_FORMAT_RGBA32F, &accumulated)) return false;
    // Measured rather than bounded: the analytic bound (grazing refraction) is ~20x too large
    // for ordinary waves and would make the wrap copies draw most of the grid several times.
    const double reach = largest_displacement(displacement);
    if (!std::isfinite(reach)) {
      ctx.fail("caustics: the refracted grid has non-finite positions (depth " +
               std::to_string(depth) + ", amplitude " + std::to_string(amplitude) +
               "); this is a bug, please report it with these parameters");
      return false;
    }
    if (!accumulate(ctx, displacement, accumulated, grid, reach)) return false;
    double scale = 1.0;
    if (ctx.param_bool(kNormalizeEnergy)) {
      const double mean = mean_intensity(accumulated);
      // Flat water gives a mean of exactly 1 and stays untouched; a mean of 0 cannot happen
      // (every pixel centre is covered) but would leave the image as it is rather than blow up.
      if (mean > 0.0 && std::isfinite(mean)) scale = 1.0 / mean;
    }
    return resolve(ctx, accumulated, out, scale);
  }

  // The exact box filter of the piecewise-linear refraction map (see README): light in whole
  // counts, shared by area of overlap, minus the counts of flat water.
  bool coverage_estimate(aq::Context& ctx, const aq_image& displacement, const aq_image& out,
                         int grid) {
    const int resolution = out.width;
    // Every count of the tile fits in 31 bits, so a texel's difference from flat water does too.
    const double triangles = 2.0 * double(grid) * grid;
    const auto flux = static_cast<GLuint>(std::floor(double(0x7fffffff) / triangles));
    if (flux < 1) {
      ctx.fail("caustics: parameter 'grid' (" + std::to_string(grid) +
               ") is too fine for 32-bit light counts; use at most 32768");
      return false;
    }
    aq_image counts, cells;
    if (!ctx.scratch(resolution, resolution, AQ_FORMAT_R32UI, &counts)) return false;
    if (!ctx.scratch(grid, grid, AQ_FORMAT_R32F, &cells)) return false;  // draw target only
    coverage_source = "#define AQ_WINDOW " + std::to_string(ctx.param_int(kWindow)) + "\n" +
                      shaders::caustics_coverage_frag.text;
    const aq_shader_source coverage{shaders::caustics_coverage_frag.name, coverage_source.c_str(),
                                    nullptr};
    const FlatKey key{grid, resolution, flux, ctx.raw()->gl_generation,
                      static_cast<int>(ctx.param_int(kWindow))};
    if (!(key == flat_key) || !flat_counts) {
      if (key.generation != flat_key.generation) flat_counts.forget();
      flat_counts.create();
      glTextureStorage2D(flat_counts.get(), 1, GL_R32UI, resolution, resolution);
      glTextureParameteri(flat_counts.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTextureParameteri(flat_counts.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      const aq_image flat{flat_counts.get(), resolution, resolution, AQ_FORMAT_R32UI};
      if (!deposit(ctx, coverage, displacement, flat, cells, grid, flux, true)) return false;
      flat_key = key;
    }
    if (!deposit(ctx, coverage, displacement, counts, cells, grid, flux, false)) return false;

    GLuint program = ctx.program(shaders::caustics_coverage_resolve_frag);
    if (program == 0) return false;
    glUseProgram(program);
    aq::bind_texture(program, "u_counts", 0, counts);
    aq::bind_texture(program, "u_flat_counts", 1,
                     aq_image{flat_counts.get(), resolution, resolution, AQ_FORMAT_R32UI});
    // One texel's worth of light: the tile's counts spread over its texels.
    aq::set_float(program, "u_intensity_per_count",
                  double(resolution) * resolution / (triangles * double(flux)));
    const bool drawn = ctx.draw(out);
    aq::unbind_textures(2);
    return drawn;
  }

  // Adds every refracted triangle's light (or, with `flat`, the undisplaced one's) to `counts`.
  static bool deposit(aq::Context& ctx, const aq_shader_source& shader,
                      const aq_image& displacement, const aq_image& counts, const aq_image& cells,
                      int grid, GLuint flux, bool flat) {
    GLuint program = ctx.program(shader);
    if (program == 0) return false;
    const GLuint zero = 0;
    glClearTexImage(counts.texture, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glUseProgram(program);
    aq::bind_texture(program, "u_displacement", 0, displacement);
    aq::set_int(program, "u_grid", grid);
    aq::set_int(program, "u_resolution", counts.width);
    glUniform1ui(glGetUniformLocation(program, "u_flux"), flux);
    aq::set_int(program, "u_identity", flat ? 1 : 0);
    glBindImageTexture(0, counts.texture, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    GLboolean mask[4];
    glGetBooleanv(GL_COLOR_WRITEMASK, mask);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);  // the atomics are the output
    const bool drawn = ctx.draw(cells);
    glColorMask(mask[0], mask[1], mask[2], mask[3]);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    aq::unbind_textures(1);
    return drawn;
  }

  // What the cached flat-water counts were made for.
  struct FlatKey {
    int grid = 0;
    int resolution = 0;
    GLuint flux = 0;
    uint32_t generation = 0;
    int window = 0;  // the same shader as the displaced counts, so flat water stays exactly 1
    bool operator==(const FlatKey&) const = default;
  };
  FlatKey flat_key;
  std::string coverage_source;  // the coverage shader with its window (outlives its compile)
  aq::gl::Texture flat_counts;  // counts of flat water (only grid, resolution, flux matter)

  bool refract_grid(aq::Context& ctx, const aq_image& target, int grid, double depth,
                    double amplitude, double eta, double time) {
    GLuint program = ctx.program(shaders::caustics_displacement_frag);
    if (program == 0) return false;
    glUseProgram(program);
    aq::set_int(program, "u_grid", grid);
    aq::set_float(program, "u_wave_scale", static_cast<double>(ctx.param_int(kWaveScale)));
    aq::set_float(program, "u_amplitude", amplitude);
    aq::set_float(program, "u_depth", depth);
    aq::set_float(program, "u_time_coord", ctx.param_float(kSpeed) * time);
    aq::set_float(program, "u_eta", eta);
    const bool drawn = ctx.draw(target);
    glUseProgram(0);
    return drawn;
  }

  bool accumulate(aq::Context& ctx, const aq_image& displacement, const aq_image& target, int grid,
                  double reach) {
    GLuint program = ctx.program(shaders::caustics_grid_vert, shaders::caustics_grid_frag);
    if (program == 0) return false;
    if (!ctx.bind_targets(&target, 1)) return false;
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearTexImage(target.texture, 0, GL_RGBA, GL_FLOAT, zero);

    if (!empty_vertex_array || vertex_array_generation != ctx.raw()->gl_generation) {
      empty_vertex_array.forget();  // a name from an old context means nothing here
      empty_vertex_array.create();
      vertex_array_generation = ctx.raw()->gl_generation;
    }
    glUseProgram(program);
    aq::bind_texture(program, "u_displacement", 0, displacement);
    aq::set_int(program, "u_grid", grid);
    aq::set_float(program, "u_max_intensity", ctx.param_float(kMaxIntensity));
    const GLint first_cell_location = glGetUniformLocation(program, "u_first_cell");
    const GLint columns_location = glGetUniformLocation(program, "u_columns");
    const GLint shift_location = glGetUniformLocation(program, "u_shift");

    const GLboolean blend_was_on = glIsEnabled(GL_BLEND);
    const GLboolean cull_was_on = glIsEnabled(GL_CULL_FACE);
    const GLboolean depth_was_on = glIsEnabled(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glDisable(GL_CULL_FACE);  // folded triangles are back-facing and must count too
    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(empty_vertex_array.get());
    // Copies of the grid shifted by whole tiles, as many rings as the largest displacement
    // needs; of each copy only the cells whose triangles can reach the tile.
    const double reach_cells = reach * grid;
    const int rings = reach > 0.0 ? static_cast<int>(std::ceil(reach + 2.0 / grid)) : 0;
    for (int sy = -rings; sy <= rings; ++sy) {
      const CellRange rows = cells_reaching_tile(sy, grid, reach_cells);
      if (rows.count <= 0) continue;
      for (int sx = -rings; sx <= rings; ++sx) {
        const CellRange columns = cells_reaching_tile(sx, grid, reach_cells);
        if (columns.count <= 0) continue;
        glUniform2i(first_cell_location, columns.first, rows.first);
        glUniform1i(columns_location, columns.count);
        glUniform2i(shift_location, sx, sy);
        glDrawArrays(GL_TRIANGLES, 0, 6 * columns.count * rows.count);
      }
    }
    glBindVertexArray(0);
    if (!blend_was_on) glDisable(GL_BLEND);
    if (cull_was_on) glEnable(GL_CULL_FACE);
    if (depth_was_on) glEnable(GL_DEPTH_TEST);
    aq::unbind_textures(1);
    return true;
  }

  // Largest |displacement| component over the grid, in tiles (NaN if any is not finite).
  static double largest_displacement(const aq_image& image) {
    std::vector<float> rg(static_cast<size_t>(image.width) * image.height * 2);
    glGetTextureImage(image.texture, 0, GL_RG, GL_FLOAT,
                      static_cast<GLsizei>(rg.size() * sizeof(float)), rg.data());
    double largest = 0.0;
    for (float v : rg) {
      if (!std::isfinite(v)) return std::nan("");
      largest = std::max(largest, double(std::abs(v)));
    }
    return largest;
  }

  // Mean of the red channel over the tile, summed in double on the CPU.
  static double mean_intensity(const aq_image& image) {
    std::vector<float> red(static_cast<size_t>(image.width) * image.height);
    glGetTextureImage(image.texture, 0, GL_RED, GL_FLOAT,
                      static_cast<GLsizei>(red.size() * sizeof(float)), red.data());
    double sum = 0.0;
    for (float v : red) sum += v;
    return sum / static_cast<double>(red.size());
  }

  static bool resolve(aq::Context& ctx, const aq_image& accumulated, const aq_image& out,
                      double scale) {
    GLuint program = ctx.program(shaders::caustics_resolve_frag);
    if (program == 0) return false;
    glUseProgram(program);
    aq::bind_texture(program, "u_accumulated", 0, accumulated);
    aq::set_float(program, "u_scale", scale);
    const bool drawn = ctx.draw(out);
    aq::unbind_textures(1);
    return drawn;
  }
};

AQ_NODE(kCausticsNode, Caustics, "caustics", "Light",
        "Tileable animated caustic texture (Stam's grid refraction): intensity = original / "
        "refracted triangle area, accumulated additively; mean 1 over the tile.",
        AQ_NODE_TIME_DEPENDENT, kInputs, kOutputs, kParams);

}  // namespace

AQ_PLUGIN("caustics", "1.0", &kCausticsNode)
