// The art-direction channels of one object (plugins/control_map/README.md):
//   control = (bleed·f_b, edge·f_e, 1 − |N·V|, [tremor > 0]·f_t),  f = clamp(1 + 2·density·fbm3, 0, 2)
// with one object-space FBM per channel (offset lattices), so the variation sticks to the object.
// The tremor channel is unitless (1 = the full screen-space tremor): the object's `tremor` is a
// length in world units for the geometry tremor, which the screen-space `tremor` node, measuring
// its amplitude in pixels, must not multiply (that turned 2 px into 0.06 px).
#include "aquarelle/noise.glsl"

// The depth pre-pass (control_map_depth.frag) laid the nearest surface and applied the cut-outs;
// this pass runs with depth test EQUAL before the shader, so hidden fragments never pay the FBM.
layout(early_fragment_tests) in;

in vec3 v_object;
in vec3 v_world;
in vec3 v_normal;
in vec2 v_uv;

layout(location = 0) out vec4 o_control;
layout(location = 1) out vec4 o_object;

uniform vec3 u_camera;
uniform vec4 u_amounts;  // bleed, edge darkening, tremor, (unused)
uniform float u_fbm_density;
uniform float u_fbm_scale;
uniform int u_octaves;

float variation(vec3 offset) {
  if (u_fbm_density <= 0.0) return 1.0;  // exactly the object's amount
  float v = aq_fbm3(v_object * u_fbm_scale + offset, u_octaves);
  return clamp(1.0 + 2.0 * u_fbm_density * v, 0.0, 2.0);
}

void main() {
  vec3 n = dot(v_normal, v_normal) > 1e-12 ? normalize(v_normal) : vec3(0.0, 1.0, 0.0);
  vec3 to_eye = u_camera - v_world;
  vec3 v = dot(to_eye, to_eye) > 1e-20 ? normalize(to_eye) : n;
  float grazing = clamp(1.0 - abs(dot(n, v)), 0.0, 1.0);
  o_control = vec4(clamp(u_amounts.x * variation(vec3(0.0)), 0.0, 1.0),
                   max(u_amounts.y * variation(vec3(101.3, 0.0, 0.0)), 0.0), grazing,
                   u_amounts.z > 0.0 ? variation(vec3(0.0, 203.7, 0.0)) : 0.0);
  o_object = vec4(v_object, 1.0);
}
