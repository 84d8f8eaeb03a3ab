// The `fast` method's cells (README "Fast method"): a texel's list where it and its +x, +y and
// +xy neighbours hold the same keys in the same slots, else -1. A full-size pixel whose four
// surrounding texels agree interpolates their values with the texture unit's bilinear filter
// instead of merging four lists.
layout(location = 0) out vec4 o_cell;

uniform sampler2D u_keys;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 size = textureSize(u_keys, 0);
  vec4 k = texelFetch(u_keys, p, 0);
  bool same = all(equal(k, texelFetch(u_keys, list_clamp(p + ivec2(1, 0), size), 0))) &&
              all(equal(k, texelFetch(u_keys, list_clamp(p + ivec2(0, 1), size), 0))) &&
              all(equal(k, texelFetch(u_keys, list_clamp(p + ivec2(1, 1), size), 0)));
  o_cell = same ? k : vec4(-1.0);
}
