// clouds: seed 002's volumetric clouds and spray, raymarched over the painted image from the
// scene's camera and depth-tested against the g-buffer:
//
//   scene camera ──► a ray per `resolution`² pixels; gbuffer depth ──► where it stops
//   3D FBM density (drifting with time, optional stepped threshold, height/distance falloff)
//   ──► τ by midpoint steps over the part of the ray the falloff leaves non-zero
//   ──► τ upsampled by depth ──► C · e^(−τ) + light colour · (1 − e^(−τ))
//
// The volume is smooth at the scale of a few pixels, so by default one ray per 4×4 pixels is
// marched and τ is upsampled with weights that follow the depth (resolution 1: the exact march,
// the bench's reference; `aquarelle bench` states the error of each resolution beside its time).
//
// density 0 passes the image through. With noise 0 and no falloff the medium is homogeneous and
// the result is Beer–Lambert's exactly (reference/clouds.h).
#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/scene_math.hpp>
#include <aquarelle/sdk/static_layer.hpp>

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "clouds_shaders.h"

namespace {

enum Input : uint32_t { kImage, kScene, kDepth };
constexpr aq_port_desc kInputs[] = {
    aq::image_port("image", "the painted image"), aq::scene_port("scene", "camera and time"),
    aq::optional_image_port("depth",
                            "gbuffer.depth: the march stops at surfaces; unconnected: "
                            "the volume lies over everything")};
constexpr aq_port_desc kOutputs[] = {aq::image_port("image", "the image with the volume over it")};
enum Param : uint32_t {
  kDensity,
  kNoise,
  kScale,
  kOctaves,
  kThreshold,
  kFalloff,
  kFalloffStart,
  kFalloffLength,
  kCentre,
  kDrift,
  kLightColor,
  kSteps,
  kMaxDistance,
  kResolution,
  kWarp
};
constexpr aq_param_desc kParams[] = {
    aq::float_param("density", 0.3, 0.0, 100.0,
                    "extinction per world unit at full density; 0 passes the image through"),
    aq::float_param("noise", 1.0, 0.0, 1.0, "0: homogeneous; 1: density fully shaped by FBM"),
    aq::float_param("scale", 0.3, 0.001, 100.0, "FBM lattice cells per world unit"),
    aq::int_param("octaves", 4, 1, 8, "FBM octaves"),
    aq::float_param("threshold", 0.0, 0.0, 1.0,
                    "shape below this is empty (the seed's stepped clouds: 0.3); 0: off"),
    aq::enum_param("falloff", "none|height|distance", 1,
                   "height: density ramps up from falloff_start over falloff_length (sky); "
                   "distance: fades out falloff_length away from `centre` (spray)"),
    aq::float_param("falloff_start", 2.0, -1000.0, 1000.0, "world y where the height ramp starts"),
    aq::float_param("falloff_length", 4.0, 0.001, 1000.0, "length of the ramp (world units)"),
    aq::vec3_param("centre", 0, 0, 0, -1000, 1000, "centre of the distance falloff (world)"),
    aq::vec3_param("drift", 0.4, 0.0, 0.15, -100, 100, "wind: world units per second"),
    aq::color_param("light_color", 1.0, 0.92, 0.8, "the volume's colour (the seed's warm clouds)"),
    aq::int_param("steps", 32, 1, 512, "raymarch steps"),
    aq::float_param("max_distance", 40.0, 0.0, 10000.0, "how far a ray marches (world units)"),
    aq::int_param("resolution", 4, 1, 16,
                  "output pixels per marched ray along each axis (τ upsampled by depth); 1: a "
                  "ray per pixel, exact"),
    aq::float_param("warp", 0.0, 0.0, 100.0,
                    "world units by which animated FBM distorts the distance falloff (the "
                    "waterfall's spray); 0: a plain sphere")};

// The density's parameters, shared by every ray of the march.
void set_volume(aq::Context& ctx, GLuint program) {
  const double* drift = ctx.param_vec3(kDrift);
  const double time = ctx.time();
  const double drifted[3] = {drift[0] * time, drift[1] * time, drift[2] * time};
  aq::set_float(program, "u_density", ctx.param_float(kDensity));
  aq::set_float(program, "u_noise", ctx.param_float(kNoise));
  aq::set_float(program, "u_scale", ctx.param_float(kScale));
  aq::set_int(program, "u_octaves", static_cast<int>(ctx.param_int(kOctaves)));
  aq::set_float(program, "u_threshold", ctx.param_float(kThreshold));
  aq::set_int(program, "u_falloff", static_cast<int>(ctx.param_enum(kFalloff)));
  aq::set_float(program, "u_falloff_start", ctx.param_float(kFalloffStart));
  aq::set_float(program, "u_falloff_length", ctx.param_float(kFalloffLength));
  aq::set_vec3(program, "u_centre", ctx.param_vec3(kCentre));
  aq::set_vec3(program, "u_drift", drifted);
  aq::set_float(program, "u_warp", ctx.param_float(kWarp));
  aq::set_float(program, "u_time", time);
  aq::set_int(program, "u_steps", static_cast<int>(ctx.param_int(kSteps)));
  aq::set_float(program, "u_max_distance", ctx.param_float(kMaxDistance));
}

class Clouds {
 public:
  int process(aq::Context& ctx) {
    const aq_image in = ctx.input_image(kImage);
    const aq_scene* scene = ctx.input_scene(kScene);
    if (scene == nullptr) {
      return ctx.fail(std::string("clouds '") + ctx.node_id() +
                      "': input `scene` is not connected; connect the scene_join's `scene`");
    }
    if (!(ctx.param_float(kDensity) > 0.0) || !(ctx.param_float(kMaxDistance) > 0.0)) {
      return ctx.pass_through(0, kImage) ? AQ_OK : AQ_ERROR;
    }
    const int cell =
        std::max(1, static_cast<int>(std::lround(static_cast<double>(ctx.param_int(kResolution)) *
                                                 ctx.render_scale())));
    const int cells_x = (in.width + cell - 1) / cell, cells_y = (in.height + cell - 1) / cell;
    aq_image out, tau;
    if (!ctx.output_like(0, in, &out) || !ctx.scratch(cells_x, cells_y, AQ_FORMAT_RGBA32F, &tau)) {
      return AQ_ERROR;
    }
    const GLuint march = ctx.program(shaders::clouds_march_frag);
    if (march == 0) return AQ_ERROR;
    const aq_camera& camera = scene->camera;
    const glm::mat4 view_projection =
        aq::scene_math::camera_projection(
            camera, static_cast<float>(in.width) / static_cast<float>(in.height)) *
        aq::scene_math::camera_view(camera);
    const glm::mat4 inverse = glm::inverse(view_projection);
    const glm::vec3 forward = glm::normalize(aq::scene_math::to_vec3(camera.target) -
                                             aq::scene_math::to_vec3(camera.position));
    const bool has_depth = ctx.connected(kDepth);
    const aq_image depth = has_depth ? ctx.input_image(kDepth) : in;
    glUseProgram(march);
    aq::bind_texture(march, "u_depth", 0, depth);
    aq::set_int(march, "u_has_depth", has_depth ? 1 : 0);
    glUniform2i(glGetUniformLocation(march, "u_size"), in.width, in.height);
    aq::set_int(march, "u_cell", cell);
    aq::set_mat4(march, "u_inverse_view_projection", glm::value_ptr(inverse));
    aq::set_vec3(march, "u_camera", camera.position);
    aq::set_vec3(march, "u_forward", glm::value_ptr(forward));
    set_volume(ctx, march);
    const glm::dmat4 view_projection_d = glm::dmat4(view_projection);
    const glm::dvec3 eye(camera.position[0], camera.position[1], camera.position[2]);
    const aq::Region live = live_pixels(ctx, view_projection_d, eye, cell, in.width, in.height);
    aq::Region damage = damaged(ctx, in, depth, has_depth, view_projection_d, live, cell);
    const Split split = split_of(damage, live, in.width, in.height);
    if (!ctx.set_draw_region(march_cells(split.composite, cell, cells_x, cells_y)))
      damage = aq::Region::everything();
    if (!ctx.draw(tau)) return AQ_ERROR;
    // Drawn even when nothing changed: the host learns that the draw applies the epilogue.
    const bool drawn = composite_into(ctx, out, in, tau, depth, has_depth, cell, split);
    ctx.set_draw_region(aq::Region::everything());
    aq::unbind_textures(3);
    return drawn && ctx.set_output_damage(0, damage) ? AQ_OK : AQ_ERROR;
  }

 private:
  // The composite's two programs draw the two parts of what changed: where a live march cell is
  // near, τ upsampled; elsewhere τ is exactly 0, and the clear program writes the image through
  // the epilogue (the same expression, without reading τ and depth: most of the paper relief's
  // pixels in the art-directed graphs). Rects grown for drawing may cover live pixels with the
  // clear program: the composite's region takes those too and is drawn after it.
  struct Split {
    aq::Region clear, composite;
  };
  static Split split_of(const aq::Region& damage, const aq::Region& live, int width, int height) {
    Split split;
    if (live.all()) {
      split.composite = damage;
      return split;
    }
    split.clear = aq::combined(damage, live, false, width, height).for_drawing();
    aq::Region composite = aq::combined(damage, live, true, width, height);
    composite.add(aq::combined(split.clear, live, true, width, height));
    split.composite = composite.for_drawing();
    return split;
  }

  bool composite_into(aq::Context& ctx, const aq_image& out, const aq_image& in,
                      const aq_image& tau, const aq_image& depth, bool has_depth, int cell,
                      const Split& split) {
    if (!split.clear.empty() && ctx.set_draw_region(split.clear)) {
      const GLuint clear =
          ctx.program(aq_shader_source{"clouds_composite.frag", clear_text_.c_str(), nullptr});
      if (clear == 0) return false;
      glUseProgram(clear);
      aq::bind_texture(clear, "u_image", 0, in);
      if (!ctx.draw(out)) return false;
    }
    const GLuint composite = ctx.program(shaders::clouds_composite_frag);
    if (composite == 0) return false;
    glUseProgram(composite);
    aq::bind_texture(composite, "u_image", 0, in);
    aq::bind_texture(composite, "u_tau", 1, tau);
    aq::bind_texture(composite, "u_depth", 2, depth);
    aq::set_int(composite, "u_has_depth", has_depth ? 1 : 0);
    aq::set_int(composite, "u_cell", cell);
    aq::set_float(composite, "u_max_distance", ctx.param_float(kMaxDistance));
    aq::set_vec3(composite, "u_light_color", ctx.param_vec3(kLightColor));
    ctx.set_draw_region(split.composite);
    return ctx.draw(out);
  }

  // Damage tracking: with the output kept and the same camera, a pixel can change where its
  // image texel changed, where a depth its four cells' rays or its own weights read changed
  // (two cells around), where the volume can be (`live`: it drifts with time), or where the
  // fused epilogue changed. Elsewhere τ is exactly 0 and the pixel its image's.
  aq::Region damaged(aq::Context& ctx, const aq_image& in, const aq_image& depth, bool has_depth,
                     const glm::dmat4& view_projection, const aq::Region& live, int cell) {
    const bool same_camera = view_projection == last_view_projection_;
    last_view_projection_ = view_projection;
    if (!ctx.output_kept(0) || !same_camera || live.all()) return aq::Region::everything();
    if (has_depth && (depth.width != in.width || depth.height != in.height))
      return aq::Region::everything();
    const int reach = 2 * cell + 1;
    aq::Region damage = ctx.input_damage(kImage);
    if (has_depth) damage.add(ctx.input_damage(kDepth).dilated(reach, reach, in.width, in.height));
    damage.add(live);
    damage.add(ctx.epilogue_damage());
    return damage.for_drawing();
  }

  // The pixels whose composite may read a march cell with τ > 0: the cells whose ray can meet
  // the falloff's non-zero part within max_distance, dilated by the composite's reach (two
  // cells). Everything without a falloff. Kept while the camera and the falloff stay.
  const aq::Region& live_pixels(aq::Context& ctx, const glm::dmat4& view_projection,
                                const glm::dvec3& eye, int cell, int width, int height) {
    const int64_t falloff = ctx.param_enum(kFalloff);
    const double start = ctx.param_float(kFalloffStart), length = ctx.param_float(kFalloffLength);
    const double warp = std::max(ctx.param_float(kWarp), 0.0);
    const double far = ctx.param_float(kMaxDistance);
    const double* c = ctx.param_vec3(kCentre);
    const glm::dvec3 centre(c[0], c[1], c[2]);
    aq::Fnv1a key;
    for (const auto& v : {falloff, int64_t{cell}, int64_t{width}, int64_t{height}}) key.mix(v);
    for (const double v : {start, length, warp, far}) key.mix(v);
    key.mix(view_projection);
    key.mix(eye);
    key.mix(centre);
    if (key.value == live_key_) return live_;
    live_key_ = key.value;
    const int reach = 2 * cell + 1;
    if (falloff == 2) {
      const double radius = (length + warp * 1.05) * 1.001 + 1e-4;  // the shader's, widened
      const glm::dvec3 oc = eye - centre;  // the shader's ray starts at the camera
      live_ = live_cells(view_projection, cell, width, height, [&](const glm::dvec3& d) {
        const double b = glm::dot(oc, d);
        const double disc = b * b - (glm::dot(oc, oc) - radius * radius);
        return !std::isfinite(disc) || (disc > 0.0 && -b + std::sqrt(disc) > 0.0);
      });
    } else if (falloff == 1) {
      // Above the ramp's start within max_distance (the march's t_end is never farther).
      const double slack = 1e-4 * (1.0 + std::abs(start));
      live_ = live_cells(view_projection, cell, width, height, [&](const glm::dvec3& d) {
        if (eye.y > start - slack) return true;
        return d.y > 0.0 && (start - eye.y) / d.y < far * 1.001 + 1e-3;
      });
    } else {
      live_ = aq::Region::everything();
    }
    live_ = live_.dilated(reach, reach, width, height);
    return live_;
  }

  // The pixels of the march cells whose ray (through the cell's centre pixel, as
  // clouds_march.frag casts it, its direction `d` unit) passes `live(d)`, tested in double one
  // cell row at a time, runs of live cells joined (a non-finite direction counts as live).
  template <typename Live>
  static aq::Region live_cells(const glm::dmat4& view_projection, int cell, int width, int height,
                               const Live& live) {
    const glm::dmat4 inverse = glm::inverse(view_projection);
    auto unproject = [&](double x, double y, double z) {
      const glm::dvec4 p = inverse * glm::dvec4(x, y, z, 1.0);
      return glm::dvec3(p) / p.w;
    };
    std::vector<aq::PixelRect> rects;
    for (int cy = 0; cy * cell < height; ++cy) {
      const int py = std::min(cy * cell + cell / 2, height - 1);
      int run = -1;
      for (int cx = 0;; ++cx) {
        bool is_live = false;
        if (cx * cell < width) {
          const int px = std::min(cx * cell + cell / 2, width - 1);
          const double x = (px + 0.5) / width * 2.0 - 1.0, y = (py + 0.5) / height * 2.0 - 1.0;
          const glm::dvec3 near_point = unproject(x, y, -1.0);
          const glm::dvec3 d = glm::normalize(unproject(x, y, 1.0) - near_point);
          is_live = !std::isfinite(d.x + d.y + d.z) || live(d);
        }
        if (is_live && run < 0) run = cx;
        if (!is_live && run >= 0) {
          rects.push_back(aq::PixelRect{run * cell, cy * cell, std::min(cx * cell, width),
                                        std::min((cy + 1) * cell, height)});
          run = -1;
        }
        if (cx * cell >= width) break;
      }
    }
    aq::Region region;
    region.add(rects);
    return region;
  }

  // The march cells the composite reads for the pixels of `damage`: a pixel reads the cell
  // under it and its neighbours at ±1.
  static aq::Region march_cells(const aq::Region& damage, int cell, int cells_x, int cells_y) {
    if (damage.all()) return damage;
    std::vector<aq::PixelRect> rects;
    for (const aq::PixelRect& r : damage.rects()) {
      rects.push_back(aq::PixelRect{std::max(r.x0 / cell - 1, 0), std::max(r.y0 / cell - 1, 0),
                                    std::min((r.x1 - 1) / cell + 2, cells_x),
                                    std::min((r.y1 - 1) / cell + 2, cells_y)});
    }
    aq::Region cells;
    cells.add(rects);
    return cells.for_drawing();
  }

  glm::dmat4 last_view_projection_{0.0};
  uint64_t live_key_ = 0;
  aq::Region live_;
  const std::string clear_text_ =
      std::string("#define AQ_CLOUDS_CLEAR 1\n") + shaders::clouds_composite_frag.text;
};

}  // namespace

AQ_NODE(kCloudsNode, Clouds, "clouds", "Watercolor",
        "Seed 002 volumetric clouds / spray: raymarched 3D FBM density (stepped threshold, height "
        "or distance falloff, drift, light colour), depth-tested against the g-buffer.",
        AQ_NODE_TIME_DEPENDENT | AQ_NODE_EPILOGUE, kInputs, kOutputs, kParams);
AQ_PLUGIN("clouds", "1.0", &kCloudsNode)
