// Segmentation and lighting of the `fast` method at half resolution: each texel averages its
// 2x2 pixels' intensity I = mask · (1 − highlight), diffuse D = I · n·l and depth Z = I · z
// (README "Layer lighting") per layer, for up to four layers (layered_lists.glsl); the layer
// is found in the GPU table by its id. It also stores, per full-size pixel, what the
// composite needs of the g-buffer there, (id, 1 − highlight, depth, 0), so the composite reads
// one texel instead of the id, normal and depth and does not light the pixel again.
layout(location = 0) out vec4 o_keys;
layout(location = 1) out vec4 o_intensity;
layout(location = 2) out vec4 o_diffuse;
layout(location = 3) out vec4 o_depth;

layout(std430, binding = 0) readonly buffer Table { uint entries[]; };

uniform sampler2D u_id;
uniform sampler2D u_normal;
uniform sampler2D u_depth;
uniform vec3 u_light;
uniform vec3 u_half;
uniform float u_shininess;
uniform float u_specular_threshold;
uniform int u_slots;
layout(rgba32f) uniform writeonly image2D u_pixels;  // per pixel (id, 1 − highlight, depth, 0)

const int kWords = 12;

// 1 + the table slot holding `id` (0: not there).
float table_key(float id) {
  uint key = floatBitsToUint(id);
  uint mask = uint(u_slots - 1);
  uint h = (key * 2654435761u) & mask;
  for (int probe = 0; probe < u_slots; ++probe) {
    uint slot = (h + uint(probe)) & mask;
    uint held = entries[slot * uint(kWords)];
    if (held == key) return float(slot + 1u);
    if (held == 0u) return 0.0;
  }
  return 0.0;
}

void main() {
  ivec2 size = textureSize(u_id, 0);
  ivec2 base = AQ_DIVISOR * ivec2(gl_FragCoord.xy);
  vec4 keys = vec4(0.0), intensity = vec4(0.0), diffuse = vec4(0.0), depth = vec4(0.0);
  for (int j = 0; j < AQ_DIVISOR; ++j) {
    for (int i = 0; i < AQ_DIVISOR; ++i) {
      ivec2 p = list_clamp(base + ivec2(i, j), size);
      float id = texelFetch(u_id, p, 0).r;
      vec3 n = texelFetch(u_normal, p, 0).xyz;
      float len = length(n);
      n = len > 1.0e-6 && len < 1.0e30 ? n / len : vec3(0.0);
      float lit_part = pow(max(dot(n, u_half), 0.0), u_shininess) >= u_specular_threshold ? 0.0 : 1.0;
      float front = texelFetch(u_depth, p, 0).r;
      imageStore(u_pixels, p, vec4(id, lit_part, front, 0.0));
      if (!(id >= 1.0 && id < 16777216.0 && floor(id) == id)) continue;
      float key = table_key(id);
      if (key < 0.5) continue;
      float lit = clamp(dot(n, u_light), 0.0, 1.0);
      float I = lit_part / float(AQ_DIVISOR * AQ_DIVISOR);
      float z = front > 0.0 && front < 3.0e38 ? front : 0.0;
      mat4 m = list_merge(keys, vec4(key, 0.0, 0.0, 0.0));
      intensity += m * vec4(I, 0.0, 0.0, 0.0);
      diffuse += m * vec4(I * lit, 0.0, 0.0, 0.0);
      depth += m * vec4(I * z, 0.0, 0.0, 0.0);
    }
  }
  o_keys = keys;
  o_intensity = intensity;
  o_diffuse = diffuse;
  o_depth = depth;
}
