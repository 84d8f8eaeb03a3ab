// The node body shared by the `erode` and `dilate` plugins: their description (ports and
// parameters) and their process(), which differ only in the fragment shader each embeds (the
// same nodes/shaders/morphology.glsl, with or without AQ_MORPH_DILATE). Header-only on top of
// plugin.hpp, so both plugins stay one self-contained file each.
//
//   image ──► pass 0 (rows) ──► span textures (one per distinct row half-width, <= 5)
//                                    │
//                                    ▼
//                             pass 1 (columns) ──► image
//
// See morphology.glsl for why the two passes give the exact square or disc extreme at a cost
// that grows with the size k rather than k².
#pragma once

#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/blocks.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

namespace aq::morphology {

enum Param : uint32_t { kSize, kFootprint, kMode, kLabels };
enum Footprint : int64_t { kSquare = 0, kDisc = 1 };
enum Mode : int64_t { kPerChannel = 0, kLuminance = 1 };
enum Labels : int64_t { kFromRegions = 0, kFromAlpha = 1 };
enum class Op { kErode, kDilate };  // which extreme the plugin's shader takes

constexpr int kMaxRadius = 4;  // size 9
constexpr int kMaxSpans = kMaxRadius + 1;

// Both ports take AQ_FORMAT_RGBA8_HDR: the encoding is monotone per channel, so the extremes
// are taken on the stored values and the image is decoded or encoded only on the last write.
// And AQ_FORMAT_RGBA8_HDR_BLOCKS: between two of these nodes (erode -> dilate -> erode) the
// image stays in the blocks the blocked path computes in, so each pass works on a quarter of
// the fragments and reads whole blocks.
// `regions` (optional): a flat colour per region (cel_light's `plain` = regions); connected, each
// pixel's window holds only the pixels of its own region, so no colour crosses an object's
// silhouette and an object thinner than the window survives (see Confine below).
inline constexpr aq_port_desc kInputs[] = {
    aq::image_port("image", "colour to filter", AQ_PORT_HDR8 | AQ_PORT_BLOCKS | AQ_PORT_DEFER_AXIS),
    aq_port_desc{"regions", AQ_PORT_IMAGE, AQ_PORT_OPTIONAL | AQ_PORT_8BIT_ENOUGH,
                 "flat colour per region (cel_light.plain with plain = regions); connected, "
                 "each window keeps to the pixel's own region"}};
enum Input : uint32_t { kImage = 0, kRegions = 1 };
inline constexpr aq_port_desc kOutputs[] = {
    aq::image_port("image", "filtered colour", AQ_PORT_HDR8 | AQ_PORT_BLOCKS | AQ_PORT_DEFER_AXIS)};
inline constexpr aq_param_desc kParams[] = {
    aq::int_param("size", 3, 1, 2 * kMaxRadius + 1,
                  "window diameter in pixels, odd (1, 3, 5, 7, 9); 1 passes the image through"),
    aq::enum_param("footprint", "square|disc", kSquare,
                   "square: the size x size window; disc: the pixels whose centres lie within "
                   "size/2 of the centre"),
    aq::enum_param("mode", "channel|luminance", kPerChannel,
                   "channel: each of r, g, b, a on its own (the seed's choice); luminance: "
                   "whole colours ordered by luminance, so no new colour appears"),
    aq::enum_param("labels", "regions|alpha", kFromRegions,
                   "where the windows' region labels come from: regions: hashed from the "
                   "`regions` input's colours (no confinement when it is unconnected); alpha: "
                   "the image's alpha holds them (cel_light with alpha = regions), so no region "
                   "image is read")};

// Which row span every row offset of the footprint uses.
struct SpanPlan {
  int radius = 0;
  int span_count = 0;
  std::array<int, kMaxSpans> half_widths{};        // distinct, ascending
  std::array<int, 2 * kMaxRadius + 1> row_span{};  // span index for dy = i - radius
};

// Half-width of the footprint's row at offset dy: the square keeps every row full; the disc of
// diameter `size` holds (dx, dy) with dx² + dy² <= (size / 2)², i.e. 4(dx² + dy²) <= size².
inline int row_half_width(int radius, int dy, Footprint footprint) {
  if (footprint == kSquare) return radius;
  const int size = 2 * radius + 1;
  int w = 0;
  while (4 * ((w + 1) * (w + 1) + dy * dy) <= size * size) ++w;
  return w;
}

inline SpanPlan plan_spans(int radius, Footprint footprint) {
  SpanPlan plan;
  plan.radius = radius;
  std::array<int, 2 * kMaxRadius + 1> widths{};
  for (int dy = -radius; dy <= radius; ++dy)
    widths[dy + radius] = row_half_width(radius, dy, footprint);
  // The half-widths are at most `radius`, so bucket them in ascending order.
  for (int w = 0; w <= radius; ++w) {
    bool used = false;
    for (int i = 0; i <= 2 * radius; ++i) {
      if (widths[i] != w) continue;
      if (!used) plan.half_widths[plan.span_count++] = w;
      used = true;
      plan.row_span[i] = plan.span_count - 1;
    }
  }
  return plan;
}

// The shader text of one variant: the plan and order as defines before the plugin's text (see
// morphology.glsl). Variants are cached by the host like any program; they carry no source path,
// so they are not hot-reloaded.
inline std::string variant_text(const aq_shader_source& shader, int pass, const SpanPlan& plan,
                                bool luminance, bool in_hdr8, bool out_hdr8, bool blocked = false) {
  auto list = [](const int* values, int count) {
    std::string text;
    for (int i = 0; i < count; ++i) text += (i > 0 ? "," : "") + std::to_string(values[i]);
    return text;
  };
  std::array<int, kMaxSpans> widths{};
  for (int i = 0; i < kMaxSpans; ++i) widths[i] = i < plan.span_count ? plan.half_widths[i] : -1;
  return "#define AQ_MORPH_PASS " + std::to_string(pass) + "\n#define AQ_MORPH_RADIUS " +
         std::to_string(plan.radius) + "\n#define AQ_MORPH_SPAN_COUNT " +
         std::to_string(plan.span_count) + "\n#define AQ_MORPH_HALF_WIDTHS int[5](" +
         list(widths.data(), kMaxSpans) + ")\n#define AQ_MORPH_ROW_SPANS int[9](" +
         list(plan.row_span.data(), 2 * kMaxRadius + 1) + ")\n#define AQ_MORPH_LUMINANCE " +
         (luminance ? "1" : "0") + "\n#define AQ_MORPH_IN_HDR8 " + (in_hdr8 ? "1" : "0") +
         "\n#define AQ_MORPH_OUT_HDR8 " + (out_hdr8 ? "1" : "0") + "\n#define AQ_MORPH_BLOCKED " +
         (blocked ? "1" : "0") + "\n" + shader.text;
}

// Confinement to regions (the `regions` input connected, or `labels` = alpha). Each pass takes
// only the taps whose region label equals its centre pixel's; the label rides in alpha between
// the passes of a node and across a handed-on pass (AQ_PORT_DEFER_AXIS), so only a node's first
// pass reads `regions` (AQ_MORPH_LABEL) and its last one, when not handed on, writes alpha 1
// (AQ_MORPH_OPAQUE). With the labels in the input's alpha already (`from_alpha`), the first
// pass reads them like the later ones: no region image, no hash per tap.
struct Confine {
  bool on = false;
  bool from_alpha = false;
  aq_image regions{};
};

// The defines of a pass of a confined node: `first` takes the labels from `regions`, `last`
// writes alpha 1. Empty when not confined.
inline std::string confine_defines(const Confine& confine, bool first, bool last) {
  if (!confine.on) return "";
  const bool hash_regions = first && !confine.from_alpha;
  return std::string("#define AQ_MORPH_CONFINE 1\n") +
         (hash_regions ? "#define AQ_MORPH_LABEL 1\n" : "") +
         (last ? "#define AQ_MORPH_OPAQUE 1\n" : "");
}

// Binds `regions` to texture unit `unit` of `program` when the pass reads labels.
inline void bind_regions(GLuint program, const Confine& confine, bool first, GLuint unit) {
  if (confine.on && first && !confine.from_alpha)
    aq::bind_texture(program, "u_regions", unit, confine.regions);
}

// Whether the blocked fast path applies: a square window, per channel, on 8-bit values (where
// packUnorm4x8 holds a texel exactly). AQUARELLE_MORPH_BLOCKED=0 turns it off (the lever table).
inline bool blocked_path(const aq_image& in, Footprint footprint, bool luminance) {
  const char* value = std::getenv("AQUARELLE_MORPH_BLOCKED");  // read per call: tests flip it
  const bool enabled = value == nullptr || std::string(value) != "0";
  return enabled && footprint == kSquare && !luminance &&
         (in.format == AQ_FORMAT_RGBA8 || in.format == AQ_FORMAT_RGBA8_HDR ||
          in.format == AQ_FORMAT_RGBA8_HDR_BLOCKS);
}

// The blocked fast path (morphology.glsl): pass 0 into a scratch image of 2 x 2 blocks over the
// blocks of the rows the columns pass reads, pass 1 over `drawn`. Either end may be in blocks
// itself (AQ_FORMAT_RGBA8_HDR_BLOCKS): pass 0 then reads blocks, pass 1 writes whole blocks.
inline bool run_blocked(aq::Context& ctx, const aq_shader_source& shader, const aq_image& in,
                        const aq_image& out, const SpanPlan& plan, const Region& drawn,
                        const Confine& confine = {}) {
  const bool in_hdr8 = in.format == AQ_FORMAT_RGBA8_HDR || in_blocks(in);
  const bool out_hdr8 = out.format == AQ_FORMAT_RGBA8_HDR || in_blocks(out);
  // The row extremes keep the input's values: encoded, or plain 8 bits from an RGBA8 input (the
  // scratch's format only gives it the blocks' layout; nobody else reads it).
  aq_image block_image;
  if (!ctx.scratch(in.width, in.height, AQ_FORMAT_RGBA8_HDR_BLOCKS, &block_image)) return false;
  const std::string rows_text = confine_defines(confine, true, false) +
                                (in_blocks(in) ? "#define AQ_MORPH_IN_BLOCKS 1\n" : "") +
                                variant_text(shader, 0, plan, false, in_hdr8, in_hdr8, true);
  const std::string columns_text = confine_defines(confine, false, true) +
                                   (in_blocks(out) ? "#define AQ_MORPH_OUT_BLOCKS 1\n" : "") +
                                   variant_text(shader, 1, plan, false, in_hdr8, out_hdr8, true);
  const GLuint rows = ctx.program(aq_shader_source{shader.name, rows_text.c_str(), nullptr});
  const GLuint columns = ctx.program(aq_shader_source{shader.name, columns_text.c_str(), nullptr});
  if (rows == 0 || columns == 0) return false;

  // The columns pass computes whole blocks when it writes blocks: the rows pass covers the rows
  // of their windows.
  const Region computed = in_blocks(out) ? whole_blocks(drawn, out.width, out.height) : drawn;
  const Region rows_region = blocks_of(
      computed.all() ? computed : computed.dilated(0, plan.radius, out.width, out.height));
  glUseProgram(rows);
  if (in_blocks(in)) {
    bind_blocks(rows, in, in);
  } else {
    aq::bind_texture(rows, "u_image", 0, in);
  }
  bind_regions(rows, confine, true, 1);
  ctx.set_draw_region(rows_region.for_drawing());
  if (!ctx.bind_targets(&block_image, 1)) {
    aq::unbind_textures(2);
    return false;
  }
  ctx.raw()->host->draw_fullscreen(ctx.raw()->host_data);

  glUseProgram(columns);
  bind_blocks(columns, block_image, in);
  ctx.set_draw_region(in_blocks(out) ? blocks_of(drawn).for_drawing() : drawn);
  const bool ok = ctx.draw(out);
  aq::unbind_textures(2);
  return ok;
}

// `from` in 2 x 2 blocks as encoded pixels in a new scratch image `to`, or `from`'s pixels into
// `to` in blocks: the blocked passes with a radius of 0, for the paths that work on pixels.
inline bool convert_blocks(aq::Context& ctx, const aq_shader_source& shader, const aq_image& from,
                           aq_image* to) {
  if (in_blocks(from) && !ctx.scratch(from.width, from.height, AQ_FORMAT_RGBA8_HDR, to))
    return false;
  return run_blocked(ctx, shader, from, *to, plan_spans(0, kSquare), Region::everything());
}

// The two plain passes (pass 0 into one span texture per row half-width, pass 1 combining them)
// from `in` into `out`, both in pixels.
inline int run_plain(aq::Context& ctx, const aq_shader_source& shader, const aq_image& in,
                     const aq_image& out, const SpanPlan& plan, bool luminance, const Region& drawn,
                     const Confine& confine) {
  const bool in_hdr8 = in.format == AQ_FORMAT_RGBA8_HDR;
  const bool out_hdr8 = out.format == AQ_FORMAT_RGBA8_HDR;
  std::array<aq_image, kMaxSpans> spans{};
  for (int i = 0; i < plan.span_count; ++i) {
    if (!ctx.scratch(in.width, in.height, in_hdr8 ? in.format : ctx.working_format(), &spans[i]))
      return AQ_ERROR;
  }
  const std::string rows_text = confine_defines(confine, true, false) +
                                variant_text(shader, 0, plan, luminance, in_hdr8, in_hdr8);
  const std::string columns_text = confine_defines(confine, false, true) +
                                   variant_text(shader, 1, plan, luminance, in_hdr8, out_hdr8);
  const GLuint rows = ctx.program(aq_shader_source{shader.name, rows_text.c_str(), nullptr});
  const GLuint columns = ctx.program(aq_shader_source{shader.name, columns_text.c_str(), nullptr});
  if (rows == 0 || columns == 0) return AQ_ERROR;

  // Pass 0: every row span at once, one colour attachment each.
  ctx.set_draw_region(
      drawn.all() ? drawn : drawn.dilated(0, plan.radius, out.width, out.height).for_drawing());
  glUseProgram(rows);
  aq::bind_texture(rows, "u_image", 0, in);
  bind_regions(rows, confine, true, 1);
  if (!ctx.bind_targets(spans.data(), static_cast<uint32_t>(plan.span_count))) {
    aq::unbind_textures(2);
    return AQ_ERROR;
  }
  ctx.raw()->host->draw_fullscreen(ctx.raw()->host_data);

  // Pass 1: combine the spans down the columns.
  glUseProgram(columns);
  std::array<GLint, kMaxSpans> units{};
  for (int i = 0; i < plan.span_count; ++i) {
    units[i] = i;
    glActiveTexture(GL_TEXTURE0 + i);
    glBindTexture(GL_TEXTURE_2D, spans[i].texture);
  }
  glUniform1iv(glGetUniformLocation(columns, "u_spans"), plan.span_count, units.data());
  ctx.set_draw_region(drawn);
  const bool ok = ctx.draw(out);
  aq::unbind_textures(kMaxSpans);
  return ok ? AQ_OK : AQ_ERROR;
}

// One blocked pass (`pass`: 0 rows, 1 columns) from `in` (blocks, or pixels for a rows pass)
// into `target`, over the pixels `region` (for_drawing: blocks where `target` is in blocks);
// `prefix`: defines before the variant's own.
inline bool draw_blocked_pass(aq::Context& ctx, const aq_shader_source& shader,
                              const std::string& prefix, int pass, const SpanPlan& plan,
                              const aq_image& in, const aq_image& target, const Region& region,
                              const Confine& confine = {}, bool first = false, bool last = false) {
  const bool out_hdr8 = target.format == AQ_FORMAT_RGBA8_HDR || in_blocks(target);
  const std::string text =
      confine_defines(confine, first, last) + prefix +
      (in_blocks(in) ? "#define AQ_MORPH_IN_BLOCKS 1\n" : "") +
      (pass == 1 && in_blocks(target) ? "#define AQ_MORPH_OUT_BLOCKS 1\n" : "") +
      variant_text(shader, pass, plan, false, true, pass == 0 || out_hdr8, true);
  const GLuint program = ctx.program(aq_shader_source{shader.name, text.c_str(), nullptr});
  if (program == 0) return false;
  glUseProgram(program);
  if (in_blocks(in)) {
    bind_blocks(program, in, in);
  } else {
    aq::bind_texture(program, "u_image", 0, in);
  }
  bind_regions(program, confine, first, 1);
  ctx.set_draw_region(in_blocks(target) ? blocks_of(region).for_drawing() : region);
  const bool ok = ctx.draw(target);
  aq::unbind_textures(2);
  return ok;
}

// Neighbourhood fusion (AQ_PORT_DEFER_AXIS): one pass from blocks to blocks along `pending`'s
// axis: the 1D pass the input's writer left undone, then this node's own pass of radius `radius`
// along the same axis (0: the writer's pass alone), over the blocks of `region`.
inline bool run_fused_axis(aq::Context& ctx, const aq_shader_source& shader, const aq_image& in,
                           const aq_image& target, const aq_axis_pass& pending, int radius,
                           const Region& region, const Confine& confine) {
  const std::string prefix = "#define AQ_MORPH_PENDING_RADIUS " + std::to_string(pending.radius) +
                             "\n#define AQ_MORPH_PENDING_DILATE " +
                             (pending.dilate != 0 ? "1" : "0") +
                             "\n#define AQ_MORPH_OUT_BLOCKS 1\n";
  return draw_blocked_pass(ctx, shader, prefix, pending.axis, plan_spans(radius, kSquare), in,
                           target, region, confine);
}

// The blocked path when a 1D pass moves across the node's boundaries: the input's writer left
// `pending` undone, and/or this node may leave its own last pass to its reader (`defer`). Runs
// the same-axis passes at a boundary as one (run_fused_axis): the morphology chain erode ->
// dilate -> erode takes four passes instead of six, with the same bits. `drawn`: the pixels of
// the output to compute.
inline bool run_handing_over(aq::Context& ctx, const aq_shader_source& shader, Op op,
                             const aq_image& in, const aq_image& out, const SpanPlan& plan,
                             const Region& drawn, const std::optional<aq_axis_pass>& pending,
                             bool defer, const Confine& confine) {
  const int r = plan.radius;
  const Region computed = in_blocks(out) ? whole_blocks(drawn, out.width, out.height) : drawn;
  const aq_axis_pass own_last{pending ? 1 - pending->axis : 1, op == Op::kDilate ? 1 : 0, r};
  if (!pending) {  // only the rows pass, straight into the output; the columns pass is the reader's
    return draw_blocked_pass(ctx, shader, "", 0, plan, in, out, computed, confine, true) &&
           ctx.defer_axis(0, own_last);
  }
  if (defer) {  // the writer's pass and this node's first, as one; this node's last is handed on
    return run_fused_axis(ctx, shader, in, out, *pending, r, computed, confine) &&
           ctx.defer_axis(0, own_last);
  }
  aq_image first;
  if (!ctx.scratch(in.width, in.height, AQ_FORMAT_RGBA8_HDR_BLOCKS, &first)) return false;
  const Region first_region = own_last.axis == 1 ? computed.dilated(0, r, out.width, out.height)
                                                 : computed.dilated(r, 0, out.width, out.height);
  if (!run_fused_axis(ctx, shader, in, first, *pending, r, first_region, confine)) return false;
  // The usual columns pass, into blocks or pixels.
  if (own_last.axis == 1)
    return draw_blocked_pass(ctx, shader, "", 1, plan, first, out, drawn, confine, false, true);
  // The rows pass last: blocks to blocks, then to pixels if the output wants them.
  if (in_blocks(out))
    return draw_blocked_pass(ctx, shader, "#define AQ_MORPH_OUT_BLOCKS 1\n", 0, plan, first, out,
                             computed, confine, false, true);
  aq_image rows;
  if (!ctx.scratch(in.width, in.height, AQ_FORMAT_RGBA8_HDR_BLOCKS, &rows)) return false;
  return draw_blocked_pass(ctx, shader, "#define AQ_MORPH_OUT_BLOCKS 1\n", 0, plan, first, rows,
                           computed, confine, false, true) &&
         run_blocked(ctx, shader, rows, out, plan_spans(0, kSquare), drawn);
}

// What a node instance has already told the user (each warning once, not every frame).
struct Warned {
  bool unread_regions = false;
};

// Runs erosion or dilation, whichever `shader` implements.
inline int run(aq::Context& ctx, const aq_shader_source& shader, Op op, Warned& warned) {
  aq_image in = ctx.input_image(0);
  const int64_t size = ctx.param_int(kSize);
  if (size < 1 || size > 2 * kMaxRadius + 1 || size % 2 == 0) {
    return ctx.fail("parameter 'size' is " + std::to_string(size) +
                    ": use an odd size from 1 to 9 (1, 3, 5, 7 or 9) so the window is centred "
                    "on the pixel");
  }
  // The input's writer may have left its last 1D pass to this node (AQ_PORT_DEFER_AXIS).
  const std::optional<aq_axis_pass> pending = ctx.input_deferred_axis(0);
  // The host stores the output in 2 x 2 blocks when every reader takes them (AQ_PORT_BLOCKS),
  // else encoded or in the working format.
  aq_image out;
  if (!ctx.output_like(0, in, &out)) return AQ_ERROR;
  if (size == 1 && out.format == in.format && !pending)
    return ctx.pass_through(0, 0) ? AQ_OK : AQ_ERROR;
  // `size` is in output pixels; a proxy render keeps at least a radius of 1 so the effect
  // does not vanish. Size 1 into another format than the input's only converts it.
  const int radius =
      size == 1 ? 0
                : std::max(1, static_cast<int>(
                                  std::lround(static_cast<double>(size / 2) * ctx.render_scale())));
  const auto footprint = static_cast<Footprint>(ctx.param_enum(kFootprint));
  const SpanPlan plan = plan_spans(radius, footprint == kDisc ? kDisc : kSquare);
  const bool luminance = ctx.param_enum(kMode) == kLuminance;
  Confine confine;
  confine.from_alpha = ctx.param_enum(kLabels) == kFromAlpha;
  confine.on = confine.from_alpha || ctx.connected(kRegions);
  if (confine.on && !confine.from_alpha) confine.regions = ctx.input_image(kRegions);
  if (confine.from_alpha && ctx.connected(kRegions) && !warned.unread_regions) {
    warned.unread_regions = true;
    ctx.warn(std::string("'") + ctx.node_id() +
             "': `labels` is alpha, so the `regions` input is not read; disconnect it or set "
             "`labels` to regions");
  }

  // Damage tracking: with its output kept, only the pixels whose window holds a changed input
  // pixel are redrawn (and the writer's pass this node runs widens the window along its axis);
  // the rows pass covers the rows the columns pass reads around them.
  Region damage = Region::everything();
  if (ctx.output_kept(0) && in.width == out.width && in.height == out.height) {
    const int reach_x = radius + (pending && pending->axis == 0 ? pending->radius : 0);
    const int reach_y = radius + (pending && pending->axis == 1 ? pending->radius : 0);
    Region changed = ctx.input_damage(kImage);
    if (confine.on && !confine.from_alpha)
      changed.add(ctx.input_damage(kRegions));  // a label moves the windows
    damage = changed.dilated(reach_x, reach_y, out.width, out.height);
  }
  if (damage.empty()) return ctx.set_output_damage(0, damage) ? AQ_OK : AQ_ERROR;
  Region drawn = damage.for_drawing();
  if (!ctx.set_draw_region(drawn.dilated(0, radius, out.width, out.height).for_drawing()))
    damage = drawn = Region::everything();
  const bool blocked = blocked_path(in, footprint == kDisc ? kDisc : kSquare, luminance);
  // Handed on, the output holds encoded row extremes: so the input must be encoded too (plain
  // 8-bit input is encoded only by the columns pass).
  const bool encoded_in = in.format == AQ_FORMAT_RGBA8_HDR || in_blocks(in);
  const bool defer =
      blocked && encoded_in && radius >= 1 && in_blocks(out) && ctx.may_defer_axis(0);
  if (blocked && (pending || defer)) {
    if (!run_handing_over(ctx, shader, op, in, out, plan, drawn, pending, defer, confine))
      return AQ_ERROR;
    return ctx.set_output_damage(0, damage) ? AQ_OK : AQ_ERROR;
  }
  if (pending) {  // a disc or the luminance order: the writer's pass first, on its own
    aq_image completed;
    if (!ctx.scratch(in.width, in.height, AQ_FORMAT_RGBA8_HDR_BLOCKS, &completed)) return AQ_ERROR;
    if (!run_fused_axis(ctx, shader, in, completed, *pending, 0, Region::everything(), confine))
      return AQ_ERROR;
    in = completed;
    damage = drawn = Region::everything();
    ctx.set_draw_region(Region::everything());
  }
  if (blocked) {
    if (!run_blocked(ctx, shader, in, out, plan, drawn, confine)) return AQ_ERROR;
    return ctx.set_output_damage(0, damage) ? AQ_OK : AQ_ERROR;
  }

  // The plain passes work on pixels: an input in blocks is unpacked first and an output in
  // blocks packed last, both whole (a disc or luminance order after a square's blocks).
  aq_image source = in, target = out;
  if (in_blocks(in) && !convert_blocks(ctx, shader, in, &source)) return AQ_ERROR;
  if (in_blocks(out)) {
    damage = drawn = Region::everything();
    if (!ctx.scratch(out.width, out.height, AQ_FORMAT_RGBA8_HDR, &target)) return AQ_ERROR;
  }
  if (run_plain(ctx, shader, source, target, plan, luminance, drawn, confine) != AQ_OK)
    return AQ_ERROR;
  if (in_blocks(out) && !convert_blocks(ctx, shader, target, &out)) return AQ_ERROR;
  return ctx.set_output_damage(0, damage) ? AQ_OK : AQ_ERROR;
}

}  // namespace aq::morphology
