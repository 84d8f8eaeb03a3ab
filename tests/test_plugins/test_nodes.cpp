// Test node types: `test_add` (optional image in, adds `offset`), `test_fail` (always reports
// an error), `test_bad_shader` (a shader that does not compile), `test_time` (time-dependent).
#include <aquarelle/plugin.hpp>

#include "test_nodes_shaders.h"

namespace {

constexpr aq_port_desc kImageIn[] = {aq::optional_image_port("image", "input")};
constexpr aq_port_desc kImageOut[] = {aq::image_port("image", "output")};
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

}  // namespace

AQ_NODE(kAdd, Add, "test_add", "Test", "adds offset", AQ_NODE_POINTWISE, kImageIn, kImageOut,
        kAddParams);
AQ_NODE(kTime, TimeAdd, "test_time", "Test", "adds offset + time", AQ_NODE_TIME_DEPENDENT,
        kImageIn, kImageOut, kAddParams);
AQ_NODE_NO_PARAMS(kFail, Fail, "test_fail", "Test", "always fails", 0, kImageIn, kImageOut);
AQ_NODE_NO_PARAMS(kBad, BadShader, "test_bad_shader", "Test", "shader error", 0, kImageIn,
                  kImageOut);
AQ_PLUGIN("test_nodes", "1.0", &kAdd, &kTime, &kFail, &kBad)
