// fog: exponential fog towards a water colour (seed 001, Coleman & Dodson), with per-object
// emission from the id buffer so bright objects (the seed's bioluminescent jellyfish) stay
// visible further away: their visibility v becomes v^(1 - emission).
#include <aquarelle/plugin.hpp>

#include <cctype>
#include <string>
#include <vector>

#include "fog_shaders.h"

namespace {

constexpr aq_port_desc kInputs[] = {
    aq::image_port("image", "colour to fog"),
    aq::image_port("depth",
                   "linear view depth (R32F, scene units); <= 0 or not finite is "
                   "background, fully fogged"),
    aq::optional_image_port("id", "object ids (R32F holding integers, 0 = background)")};
constexpr aq_port_desc kOutputs[] = {aq::image_port("image", "fogged colour")};
enum Param { kColor, kDensity, kExponent, kEmissiveIds, kEmission };
constexpr aq_param_desc kParams[] = {
    aq::color_param("color", 0.0, 0.07, 0.1, "water colour the fog tends to (linear)"),
    aq::float_param("density", 0.04, 0.0, 100.0,
                    "extinction per scene unit: visibility = exp(-(density*depth)^exponent)", 0.0,
                    "log"),
    aq::float_param("exponent", 1.0, 0.1, 8.0,
                    "1: exponential fog; 2: squared exponential (clear near, thick far)"),
    aq::string_param("emissive_ids", "",
                     "object ids that glow through the fog, e.g. \"7, 12\" (needs the id input)"),
    aq::float_param("emission", 0.8, 0.0, 1.0,
                    "how much emissive objects resist the fog: visibility^(1 - emission); 1 "
                    "ignores the fog")};

constexpr size_t kMaxEmissiveIds = 32;  // u_emissive_ids in fog.frag

// Parses "7, 12 30" into ids; returns an error message, empty when fine.
std::string parse_ids(const std::string& text, std::vector<int>& ids) {
  size_t i = 0;
  while (i < text.size()) {
    if (std::isspace(static_cast<unsigned char>(text[i])) || text[i] == ',') {
      ++i;
      continue;
    }
    size_t end = i;
    while (end < text.size() && std::isdigit(static_cast<unsigned char>(text[end]))) ++end;
    if (end == i || end - i > 9) {
      return "emissive_ids \"" + text + "\": expected object ids (non-negative integers) " +
             "separated by commas or spaces, e.g. \"7, 12\"";
    }
    ids.push_back(std::stoi(text.substr(i, end - i)));
    i = end;
  }
  if (ids.size() > kMaxEmissiveIds) {
    return "emissive_ids lists " + std::to_string(ids.size()) + " ids; at most " +
           std::to_string(kMaxEmissiveIds) + " are supported";
  }
  return {};
}

struct Fog {
  bool warned_missing_id = false;

  int process(aq::Context& ctx) {
    std::vector<int> ids;
    const std::string error = parse_ids(ctx.param_string(kEmissiveIds), ids);
    if (!error.empty()) return ctx.fail(error);
    if (!ids.empty() && !ctx.connected(2) && !warned_missing_id) {
      ctx.warn("emissive_ids are set but the id input is not connected: no object glows");
      warned_missing_id = true;
    }
    if (ctx.param_float(kDensity) <= 0.0) return ctx.pass_through(0, 0) ? AQ_OK : AQ_ERROR;

    const aq_image in = ctx.input_image(0);
    aq_image out;
    if (!ctx.output_like(0, in, &out)) return AQ_ERROR;
    GLuint program = ctx.program(shaders::fog_frag);
    if (program == 0) return AQ_ERROR;
    glUseProgram(program);
    aq::bind_texture(program, "u_image", 0, in);
    aq::bind_texture(program, "u_depth", 1, ctx.input_image(1));
    if (ctx.connected(2)) aq::bind_texture(program, "u_id", 2, ctx.input_image(2));
    aq::set_int(program, "u_has_id", ctx.connected(2) ? 1 : 0);
    aq::set_vec2(program, "u_size", in.width, in.height);
    aq::set_vec3(program, "u_water", ctx.param_vec3(kColor));
    aq::set_float(program, "u_density", ctx.param_float(kDensity));
    aq::set_float(program, "u_exponent", ctx.param_float(kExponent));
    aq::set_float(program, "u_emission", ctx.param_float(kEmission));
    if (!ids.empty()) {
      glUniform1iv(glGetUniformLocation(program, "u_emissive_ids"),
                   static_cast<GLsizei>(ids.size()), ids.data());
    }
    aq::set_int(program, "u_emissive_count", static_cast<int>(ids.size()));
    const bool drawn = ctx.draw(out);
    aq::unbind_textures(3);
    return drawn ? AQ_OK : AQ_ERROR;
  }
};

}  // namespace

AQ_NODE(kFogNode, Fog, "fog", "Color",
        "Exponential fog towards a water colour by depth; listed object ids glow through it.",
        AQ_NODE_POINTWISE, kInputs, kOutputs, kParams);
AQ_PLUGIN("fog", "1.0", &kFogNode)
