// Test node types: `test_add` (optional image in, adds `offset`), `test_fail` (always reports
// an error), `test_bad_shader` (a shader that does not compile), `test_time` (time-dependent),
// `test_square` (a square moving with the frame, redrawn only where it was and is: damage
// tracking), `test_rects` (a draw region of 40 rects over a background).
#include <aquarelle/plugin.hpp>

#include <optional>
#include <utility>

#include "test_nodes_shaders.h"

namespace {

constexpr aq_port_desc kImageIn[] = {aq::optional_image_port("image", "input")};
constexpr aq_port_desc kImageOut[] = {aq::image_port("image", "output")};
constexpr aq_param_desc kSquareParams[] = {aq::int_param("size", 6, 1, 64, "side in pixels")};
constexpr aq_param_desc kRectsParams[] = {
    aq::bool_param("own_vertex", false, "draw with the node's own full-screen vertex shader")};
constexpr aq_param_desc kAddParams[] = {
    aq::float_param("offset", 0.0, -10.0, 10.0, "added to rgb")};

struct Add {
  int process(aq::Context& ctx) {
    aq_image in = ctx.input_image(0);
    int w = ctx.connected(0) ? in.width : ctx.width();
    int h = ctx.connected(0) ? in.height : ctx.height();
    aq_image out;
    if (!ctx.output(0, w, h, ctx.working_format(), &out)) return AQ_ERROR;
    GLuint program = ctx.program(shaders::test_add_frag);
    if (program == 0) return AQ_ERROR;
    glUseProgram(program);
    aq::bind_texture(program, "u_image", 0, in);
    aq::set_int(program, "u_has_image", ctx.connected(0) ? 1 : 0);
    aq::set_float(program, "u_offset",
                  ctx.param_float(0) + (ctx.raw()->frame > 0 && time_dependent ? ctx.time() : 0));
    return ctx.draw(out) ? AQ_OK : AQ_ERROR;
  }
  bool time_dependent = false;
};

struct TimeAdd : Add {
  TimeAdd() { time_dependent = true; }
};

struct Fail {
  int process(aq::Context& ctx) { return ctx.fail("this node always fails (test)"); }
};

const aq_shader_source kBrokenShader = {"broken.frag",
                                        "in vec2 v_uv;\nout vec4 o_color;\nvoid main() {\n"
                                        "  o_color = vec4(undefined_name);\n}\n",
                                        nullptr};
struct BadShader {
  int process(aq::Context& ctx) {
    aq_image out;
    if (!ctx.output(0, 4, 4, ctx.working_format(), &out)) return AQ_ERROR;
    return ctx.program(kBrokenShader) == 0 ? AQ_ERROR : AQ_OK;
  }
};

// A `size`-pixel square at x = 4 + 5 * frame over a gradient. With its output kept it redraws only
// the square's last and new place and says so (aq_host::set_output_damage).
struct Square {
  int process(aq::Context& ctx) {
    aq_image out;
    if (!ctx.output(0, ctx.width(), ctx.height(), ctx.working_format(), &out)) return AQ_ERROR;
    const int x0 = 4 + 5 * ctx.frame(), y0 = out.height / 3;
    const int side = static_cast<int>(ctx.param_int(0));
    const aq::PixelRect now{x0, y0, x0 + side, y0 + side};
    aq::Region damage = aq::Region::everything();
    if (ctx.output_kept(0) && drawn_ && size_ == std::make_pair(out.width, out.height)) {
      damage = aq::Region::of(*drawn_);
      damage.add(now);
      damage = damage.dilated(0, 0, out.width, out.height);  // clipped to the image
    }
    GLuint program = ctx.program(shaders::test_square_frag);
    if (program == 0) return AQ_ERROR;
    glUseProgram(program);
    glUniform4f(glGetUniformLocation(program, "u_square"), static_cast<float>(now.x0),
                static_cast<float>(now.y0), static_cast<float>(now.x1), static_cast<float>(now.y1));
    if (!ctx.set_draw_region(damage)) damage = aq::Region::everything();
    if (!ctx.draw(out)) return AQ_ERROR;
    drawn_ = now;
    size_ = {out.width, out.height};
    return ctx.set_output_damage(0, damage) ? AQ_OK : AQ_ERROR;
  }
  std::optional<aq::PixelRect> drawn_;
  std::pair<int, int> size_{0, 0};
};

// 0.25 everywhere, then 1 in a draw region of 40 rects of 2 x 3 pixels: (4i + 1, 6j + 1) for
// i < 10, j < 4. With `own_vertex` the program has the node's own vertex shader, which the host
// cannot batch: draw_fullscreen then draws the rects one by one.
const aq_shader_source kOwnVertex = {
    "own_fullscreen.vert",
    "void main() {\n"
    "  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));\n"
    "  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);\n}\n",
    nullptr};
struct Rects {
  int process(aq::Context& ctx) {
    aq_image out;
    if (!ctx.output(0, 48, 32, AQ_FORMAT_RGBA32F, &out)) return AQ_ERROR;
    const aq_host* host = ctx.raw()->host;
    const GLuint program = ctx.param_bool(0) ? host->program(ctx.raw()->host_data, &kOwnVertex,
                                                             &shaders::test_rects_frag)
                                             : ctx.program(shaders::test_rects_frag);
    if (program == 0) return AQ_ERROR;
    glUseProgram(program);
    glUniform4f(glGetUniformLocation(program, "u_color"), 0.25f, 0.25f, 0.25f, 1.0f);
    if (!ctx.draw(out)) return AQ_ERROR;
    aq::Region rects;
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 10; ++i)
        rects.add(aq::PixelRect{4 * i + 1, 6 * j + 1, 4 * i + 3, 6 * j + 4});
    if (!ctx.set_draw_region(rects)) return AQ_ERROR;
    glUniform4f(glGetUniformLocation(program, "u_color"), 1.0f, 1.0f, 1.0f, 1.0f);
    return ctx.draw(out) ? AQ_OK : AQ_ERROR;
  }
};

}  // namespace

AQ_NODE(kAdd, Add, "test_add", "Test", "adds offset", AQ_NODE_POINTWISE, kImageIn, kImageOut,
        kAddParams);
AQ_NODE(kTime, TimeAdd, "test_time", "Test", "adds offset + time", AQ_NODE_TIME_DEPENDENT, kImageIn,
        kImageOut, kAddParams);
AQ_NODE_NO_PARAMS(kFail, Fail, "test_fail", "Test", "always fails", 0, kImageIn, kImageOut);
AQ_NODE_NO_PARAMS(kBad, BadShader, "test_bad_shader", "Test", "shader error", 0, kImageIn,
                  kImageOut);
AQ_SOURCE_NODE(kSquare, Square, "test_square", "Test", "a square moving with the frame",
               AQ_NODE_TIME_DEPENDENT, kImageOut, kSquareParams);
AQ_SOURCE_NODE(kRects, Rects, "test_rects", "Test", "a draw region of 40 rects", 0, kImageOut,
               kRectsParams);
AQ_PLUGIN("test_nodes", "1.0", &kAdd, &kTime, &kFail, &kBad, &kSquare, &kRects)
