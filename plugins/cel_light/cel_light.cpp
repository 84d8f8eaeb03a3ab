// cel_light: the deferred "Light" pass of Paré-Vogt & Chaid (§2.3, §3.1, §4.3): diffuse light
// from the scene's directional light plus ambient, the shadow-map test (with optional PCF),
// the caustic texture projected along the light onto lit surfaces, then cel shading: the HSV
// value quantised to `levels` with hue and saturation kept. Output is linear HDR.
//
//   scene ──► light direction, colour, ambient, light matrix (scene_math.hpp, as shadowmap)
//   surface (or position, normal, albedo, id) ┐
//   (the packed surface carries the depth: the position is rebuilt on the camera's rays)
//   shadow (optional) ─────────────┼──► cel_light.frag ──► image (working format)
//   caustics (optional) ───────────┘                    └─► plain (the same without caustics)
#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/gl_raii.hpp>
#include <aquarelle/sdk/scene_math.hpp>
#include <aquarelle/sdk/static_layer.hpp>  // Fnv1a

#include <glm/gtc/type_ptr.hpp>

#include <string>
#include <vector>

#include "cel_light_shaders.h"

namespace {

enum Input { kScene, kPosition, kNormal, kAlbedo, kId, kShadow, kCaustics, kSurface };
constexpr aq_port_desc kInputs[] = {
    aq::scene_port("scene", "light direction, colour and ambient; the light matrix"),
    aq::optional_image_port("position",
                            "world position (gbuffer.position), with `normal`, `albedo` and "
                            "`id`; not read with `surface`, which carries the depth"),
    aq::optional_image_port("normal", "world normal (gbuffer.normal); or connect `surface`"),
    aq::optional_image_port("albedo", "base colour (gbuffer.albedo); or connect `surface`"),
    aq::optional_image_port("id", "object id, 0 = background (gbuffer.id); or connect `surface`"),
    aq::optional_image_port("shadow", "light-space depth (shadowmap.depth); unlit test if absent"),
    aq::optional_image_port("caustics", "tileable caustic texture, mean 1 (caustics.image)"),
    aq::optional_image_port("surface",
                            "normal, albedo, id and depth packed in one texel (gbuffer.surface): "
                            "one read instead of four; replaces `position`, `normal`, `albedo` "
                            "and `id`")};
constexpr aq_port_desc kOutputs[] = {
    // AQ_PORT_HDR8: written encoded (aquarelle/hdr8.glsl) when every reader decodes it.
    aq::image_port("image", "lit, cel-shaded colour (HDR)", AQ_PORT_HDR8),
    aq::image_port("plain",
                   "the same light without caustics; with `plain` = regions a flat colour per "
                   "object id (the source of `edge`)")};

enum Param {
  kLevels,
  kQuantize,
  kPcfRadius,
  kCausticTile,
  kCausticStrength,
  kBackground,
  kEnvironment,
  kSpace,
  kFloor,
  kPlain,
  kAlpha
};
constexpr aq_param_desc kParams[] = {
    aq::int_param("levels", 4, 1, 64,
                  "HSV value levels: v -> round(v (levels-1)) / (levels-1) in `space`; "
                  "1 = flat colour"),
    aq::bool_param("quantize", true, "apply cel shading (off: plain diffuse light)"),
    aq::int_param("pcf_radius", 1, 0, 4, "shadow filter: (2r+1)^2 taps, 0 = one tap"),
    aq::float_param("caustic_tile", 0.0, 0.0, 1000.0,
                    "world units covered by one period of the caustic texture; 0: the scene's "
                    "(scene.caustic_tile, which the caustics node sizes its texture for)"),
    aq::float_param("caustic_strength", 1.0, 0.0, 4.0,
                    "0: no caustics, 1: as computed, >1: more contrast"),
    aq::color_param("background", 0.1, 0.3, 0.4, "colour where id = 0 (open water)"),
    aq::bool_param("environment", false,
                   "where id = 0 show the scene's environment (the g-buffer albedo there, "
                   "scene_join's gradient) instead of `background`"),
    aq::enum_param("space", "display|linear", 0,
                   "where the levels are even steps: display (the sRGB-encoded value, as the "
                   "seed quantised display values) or linear (the light's value)"),
    aq::bool_param("floor", true,
                   "a lit pixel that is not black keeps at least the first level above black "
                   "(a painter never paints a lit, coloured surface black)"),
    aq::enum_param("plain", "light|regions", 0,
                   "what the `plain` output holds: light (the light without caustics) or regions "
                   "(a flat colour per object id: where washes meet, the source `edge` darkens "
                   "outlines from without lines along cel bands; no extra pass)"),
    aq::enum_param("alpha", "opaque|regions", 0,
                   "what the image's alpha holds: opaque (1) or regions (the 8-bit label of the "
                   "pixel's object region, the hash erode and dilate take of `plain` = regions): "
                   "a morphology chain with labels = alpha then reads no region image")};

// The shader variant for this node's connections and parameters (see cel_light.frag).
std::string variant_source(bool has_shadow, bool has_caustics, bool quantize, int pcf_radius,
                           bool same_size, bool encode, bool surface, bool display, bool floor,
                           bool regions, bool alpha_labels) {
  return std::string(regions ? "#define AQ_PLAIN_REGIONS 1\n" : "") +
         (alpha_labels ? "#define AQ_ALPHA_LABELS 1\n" : "") +
         "#define AQ_QUANTIZE_DISPLAY " + std::to_string(display ? 1 : 0) +
         "\n#define AQ_QUANTIZE_FLOOR " + std::to_string(floor ? 1 : 0) + "\n#define AQ_SURFACE " +
         std::to_string(surface ? 1 : 0) + "\n#define AQ_HAS_SHADOW " +
         std::to_string(has_shadow ? 1 : 0) + "\n#define AQ_HAS_CAUSTICS " +
         std::to_string(has_caustics ? 1 : 0) + "\n#define AQ_QUANTIZE " +
         std::to_string(quantize ? 1 : 0) + "\n#define AQ_PCF_RADIUS " +
         std::to_string(pcf_radius) + "\n#define AQ_SAME_SIZE " +
         std::to_string(same_size ? 1 : 0) + "\n#define AQ_ENCODE_HDR8 " +
         std::to_string(encode ? 1 : 0) + "\n" + shaders::cel_light_frag.text;
}

bool same_size(const aq_image& a, const aq_image& b) {
  return a.width == b.width && a.height == b.height;
}

struct CelLight {
  struct Variant {
    bool shadow, caustics, quantize;
    int pcf_radius;
    bool same_size;
    bool encode;
    bool surface;
    bool display, floor, regions;
    bool alpha_labels;
    bool operator==(const Variant&) const = default;
  };
  Variant variant_{};
  std::string source;  // outlives the program call that reads it
  aq::gl::Sampler repeating;
  aq::view_bounds::MeshBoxes boxes;
  uint32_t sampler_generation = 0;
  uint64_t lighting_key_ = 0;  // the scene's part of the uniforms on the last call
  bool warned_both_ = false;

  int process(aq::Context& ctx) {
    const aq_scene* scene = ctx.input_scene(kScene);
    if (scene == nullptr) {
      return ctx.fail(std::string("cel_light '") + ctx.node_id() +
                      "': input `scene` is not connected; connect the scene node that feeds "
                      "the gbuffer");
    }
    const bool packed = ctx.connected(kSurface);
    if (!packed && !(ctx.connected(kPosition) && ctx.connected(kNormal) && ctx.connected(kAlbedo) &&
                     ctx.connected(kId))) {
      return ctx.fail(std::string("cel_light '") + ctx.node_id() +
                      "': the surface is not connected; connect `surface` to the gbuffer's "
                      "`surface` output (or all of `position`, `normal`, `albedo` and `id` to its "
                      "outputs of those names)");
    }
    if (packed && ctx.input_image(kSurface).format != AQ_FORMAT_RGBA32UI) {
      return ctx.fail(std::string("cel_light '") + ctx.node_id() +
                      "': input `surface` is not a packed surface (RGBA32UI); connect a "
                      "gbuffer's `surface` output to it, or an image to `normal`/`albedo`/`id`");
    }
    if (packed &&
        (ctx.connected(kPosition) || ctx.connected(kNormal) || ctx.connected(kAlbedo) ||
         ctx.connected(kId)) &&
        !warned_both_) {
      ctx.warn(std::string("cel_light '") + ctx.node_id() +
               "': `surface` is connected, so `position`, `normal`, `albedo` and `id` are not "
               "read; disconnect them");
      warned_both_ = true;
    }
    // The g-buffer image every output is sized like: the surface, or the position.
    const aq_image gbuffer_image = ctx.input_image(packed ? kSurface : kPosition);
    aq_image targets[2];
    if (!ctx.output_like(0, gbuffer_image, &targets[0]) ||
        !ctx.output_like(1, gbuffer_image, &targets[1])) {
      return AQ_ERROR;
    }
    const bool has_shadow = ctx.connected(kShadow);
    const bool has_caustics = ctx.connected(kCaustics);
    bool gbuffer_same_size = true;
    for (uint32_t input : pixel_inputs(ctx))
      gbuffer_same_size = gbuffer_same_size && same_size(gbuffer_image, ctx.input_image(input));
    const Variant variant{has_shadow,
                          has_caustics,
                          ctx.param_bool(kQuantize),
                          static_cast<int>(ctx.param_int(kPcfRadius)),
                          gbuffer_same_size,
                          targets[0].format == AQ_FORMAT_RGBA8_HDR,
                          packed,
                          ctx.param_enum(kSpace) == 0,
                          ctx.param_bool(kFloor),
                          ctx.param_enum(kPlain) == 1,
                          ctx.param_enum(kAlpha) == 1};
    if (source.empty() || variant != variant_) {  // not re-made every frame
      source = variant_source(variant.shadow, variant.caustics, variant.quantize,
                              variant.pcf_radius, variant.same_size, variant.encode,
                              variant.surface, variant.display, variant.floor, variant.regions,
                              variant.alpha_labels);
      variant_ = variant;
    }
    // No source path: hot reload would read the file without the variant's defines.
    const aq_shader_source fragment{shaders::cel_light_frag.name, source.c_str(), nullptr};
    GLuint program = ctx.program(fragment);
    if (program == 0) return AQ_ERROR;
    glUseProgram(program);
    if (packed) {
      aq::bind_texture(program, "u_surface", 1, ctx.input_image(kSurface));
      set_camera_rays(program, scene->camera, gbuffer_image);
    } else {
      aq::bind_texture(program, "u_position", 0, gbuffer_image);
      aq::bind_texture(program, "u_normal", 1, ctx.input_image(kNormal));
      aq::bind_texture(program, "u_albedo", 2, ctx.input_image(kAlbedo));
      aq::bind_texture(program, "u_id", 3, ctx.input_image(kId));
    }
    if (has_shadow) aq::bind_texture(program, "u_shadow", 4, ctx.input_image(kShadow));
    if (has_caustics) bind_caustics(ctx, program);

    const uint64_t lighting = set_light_uniforms(ctx, program, *scene, packed, has_shadow);
    const aq::Region gbuffer = gbuffer_damage(ctx, targets[0]);
    aq::Region damage = damaged(ctx, gbuffer, lighting != lighting_key_);
    lighting_key_ = lighting;
    // The regions depend on the ids alone: they change only where the g-buffer did, though the
    // pass redraws them wherever the light changed (the same values), so their readers
    // (edge_detect) redraw only that.
    aq::Region plain_damage = variant.regions ? gbuffer : damage;
    if (!ctx.set_draw_region(damage.for_drawing()))
      damage = plain_damage = aq::Region::everything();

    const bool bound = ctx.bind_targets(targets, 2);
    if (bound) ctx.raw()->host->draw_fullscreen(ctx.raw()->host_data);
    glBindSampler(5, 0);
    aq::unbind_textures(6);
    return bound && ctx.set_output_damage(0, damage) && ctx.set_output_damage(1, plain_damage)
               ? AQ_OK
               : AQ_ERROR;
  }

  // The light's uniforms from the scene and the parameters (program bound); returns a hash of
  // the scene's part of them, whose change makes every surface's light change.
  uint64_t set_light_uniforms(aq::Context& ctx, GLuint program, const aq_scene& scene, bool packed,
                              bool has_shadow) {
    // The matrix the shadow map was drawn with: fitted to the receivers in view, for its size.
    glm::mat4 light = aq::scene_math::light_view_projection(scene);
    if (has_shadow) {
      const aq::scene_math::ViewFit fit = aq::scene_math::fit_to_view(
          scene, boxes.world_boxes(scene),
          static_cast<float>(ctx.width()) / static_cast<float>(ctx.height()));
      light = aq::scene_math::light_view_projection(scene, fit, ctx.input_image(kShadow).width);
    }
    glm::vec3 direction = aq::scene_math::light_direction(scene);
    aq::set_mat4(program, "u_light_view_projection", glm::value_ptr(light));
    aq::set_vec3(program, "u_light_direction", glm::value_ptr(direction));
    aq::set_vec3(program, "u_light_color", scene.light.color);
    aq::set_vec3(program, "u_ambient", scene.light.ambient);
    aq::set_float(program, "u_water_height", scene.water_height);
    const double own_tile = ctx.param_float(kCausticTile);
    aq::set_float(program, "u_caustic_tile",
                  own_tile > 0.0 ? own_tile : aq::scene_caustic_tile(scene));
    aq::set_float(program, "u_caustic_strength", ctx.param_float(kCausticStrength));
    aq::set_int(program, "u_levels", static_cast<int>(ctx.param_int(kLevels)));
    aq::set_vec3(program, "u_background", ctx.param_vec3(kBackground));
    aq::set_int(program, "u_environment", ctx.param_bool(kEnvironment) ? 1 : 0);

    aq::Fnv1a lighting;
    lighting.mix(light);
    lighting.mix(direction);
    lighting.mix(scene.light.color);
    lighting.mix(scene.light.ambient);
    lighting.mix(scene.water_height);
    lighting.mix(aq::scene_caustic_tile(scene));
    // From the surface's depth, the position also depends on the camera: a camera that moves
    // without changing a pixel's depth still moves its point.
    if (packed) lighting.mix(scene.camera);
    return lighting.value;
  }

  // One period of the caustics: the hardware's repeat wrap gives the periodic bilinear lookup
  // in one read (pool textures clamp at the edge).
  void bind_caustics(aq::Context& ctx, GLuint program) {
    if (!repeating || sampler_generation != ctx.raw()->gl_generation) {
      repeating.forget();  // a name from an old context means nothing here
      const GLuint sampler = repeating.create();
      glSamplerParameteri(sampler, GL_TEXTURE_WRAP_S, GL_REPEAT);
      glSamplerParameteri(sampler, GL_TEXTURE_WRAP_T, GL_REPEAT);
      glSamplerParameteri(sampler, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      glSamplerParameteri(sampler, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      sampler_generation = ctx.raw()->gl_generation;
    }
    aq::bind_texture(program, "u_caustics", 5, ctx.input_image(kCaustics));
    glBindSampler(5, repeating.get());
  }

  // The inputs a pixel's surface and position are read from.
  static std::vector<uint32_t> pixel_inputs(const aq::Context& ctx) {
    if (ctx.connected(kSurface)) return {kSurface};
    return {kPosition, kNormal, kAlbedo, kId};
  }

  // The ray through texel t of the packed surface is ray0 + t.x dx + t.y dy with a view-axis
  // component of 1 (camera_rays at the surface's aspect, the one the g-buffer drew with), so
  // the shader's position is eye + depth * ray.
  static void set_camera_rays(GLuint program, const aq_camera& camera, const aq_image& surface) {
    const double width = surface.width, height = surface.height;
    const aq::scene_math::CameraRays rays = aq::scene_math::camera_rays(camera, width / height);
    double ray0[3], dx[3], dy[3], eye[3];
    for (int axis = 0; axis < 3; ++axis) {
      // The texel's centre: ndc = (t + 0.5) * 2 / size - 1 along each axis.
      dx[axis] = rays.right[axis] * 2.0 / width;
      dy[axis] = rays.up[axis] * 2.0 / height;
      ray0[axis] = rays.forward[axis] + rays.right[axis] * (1.0 / width - 1.0) +
                   rays.up[axis] * (1.0 / height - 1.0);
      eye[axis] = camera.position[axis];
    }
    aq::set_vec3(program, "u_eye", eye);
    aq::set_vec3(program, "u_ray0", ray0);
    aq::set_vec3(program, "u_ray_dx", dx);
    aq::set_vec3(program, "u_ray_dy", dy);
  }

  // Damage tracking. Where the g-buffer inputs may have changed since the last call; everything
  // when an output was not kept or an input has another size than the target.
  aq::Region gbuffer_damage(const aq::Context& ctx, const aq_image& target) {
    if (!ctx.output_kept(0) || !ctx.output_kept(1)) return aq::Region::everything();
    aq::Region damage;
    for (uint32_t input : pixel_inputs(ctx)) {
      const aq_image image = ctx.input_image(input);
      if (image.width != target.width || image.height != target.height)
        return aq::Region::everything();
      damage.add(ctx.input_damage(input));
    }
    return damage;
  }

  // What the pass redraws: the pixels whose light can differ from the kept outputs'. A pixel
  // reads the g-buffer at itself; the shadow map, the caustics and the scene's light only where
  // a surface is (the background is the parameter's colour or the g-buffer's albedo), so a
  // change of those reaches only the id's (or surface's) bounds (where the g-buffer drew
  // meshes), not the open water.
  aq::Region damaged(const aq::Context& ctx, const aq::Region& gbuffer, bool lighting_changed) {
    aq::Region damage = gbuffer;
    bool surfaces_changed = lighting_changed;
    for (uint32_t input : {kShadow, kCaustics})
      surfaces_changed =
          surfaces_changed || (ctx.connected(input) && !ctx.input_damage(input).empty());
    if (surfaces_changed) damage.add(ctx.input_bounds(ctx.connected(kSurface) ? kSurface : kId));
    return damage;
  }
};

}  // namespace

AQ_NODE(kCelLightNode, CelLight, "cel_light", "Light",
        "Deferred diffuse light with shadow map and projected caustics, then cel shading "
        "(HSV value quantised to N levels in display space, hue and saturation kept; a lit "
        "colour never goes black).",
        0, kInputs, kOutputs, kParams);
AQ_PLUGIN("cel_light", "1.0", &kCelLightNode)
