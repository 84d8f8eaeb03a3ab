// Exponential fog towards the water colour (seed 001): visibility v = exp(-(density·z)^exponent),
// out = mix(water, colour, v). Emissive objects (ids listed by the node) see their visibility
// raised to v^(1 - emission), so they glow through the fog like seed 001's jellyfish. Depth that
// is not a positive finite number (background, NaN) is infinitely far: pure water colour.
in vec2 v_uv;
layout(location = 0) out vec4 o_color;

uniform sampler2D u_image;
uniform sampler2D u_depth;
uniform sampler2D u_id;
uniform bool u_has_id;
uniform vec2 u_size;
uniform vec3 u_water;
uniform float u_density;
uniform float u_exponent;
uniform float u_emission;
uniform int u_emissive_ids[32];
uniform int u_emissive_count;

bool is_emissive(vec2 uv) {
  if (!u_has_id || u_emissive_count == 0) return false;
  float id = texture(u_id, uv).r;
  if (!(id >= 0.0 && id < 2.0e9)) return false;  // NaN, negative or huge: not an object id
  int object = int(round(id));
  for (int i = 0; i < u_emissive_count; ++i) {
    if (u_emissive_ids[i] == object) return true;
  }
  return false;
}

void main() {
  vec4 c = texelFetch(u_image, ivec2(gl_FragCoord.xy), 0);
  vec2 uv = gl_FragCoord.xy / u_size;  // depth and id may have another size than the image
  float z = texture(u_depth, uv).r;
  float visibility = 0.0;
  if (z > 0.0 && z <= 3.0e38) {
    // v^(1 - emission) taken in the exponent, so emission 1 is exactly 1 even where v underflows.
    float optical_depth = min(pow(u_density * z, u_exponent), 1.0e30);  // inf * 0 would be NaN
    if (is_emissive(uv)) optical_depth *= 1.0 - u_emission;
    visibility = exp(-optical_depth);
  }
  o_color = vec4(mix(u_water, c.rgb, visibility), c.a);
}
