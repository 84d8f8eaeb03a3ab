// The `fast` method's cells and slots (README "Fast method"), drawn into a strip four texels
// of the lists wide per texel:
//   x in [0, W): the cell, a texel's list where it and its +x, +y and +xy neighbours hold the
//                same keys in the same slots, else -1;
//   x in [kW, (k+1)W), k = 1..4: slot k-1's (b, bd, bz, blurred wet edge) of that texel.
// A full-size pixel whose four surrounding texels agree reads its cell, then per layer one
// bilinear fetch of the slot's values (the texture unit interpolates, and the strip's parts
// never meet inside an agreeing cell) instead of merging four lists of five values.
layout(location = 0) out vec4 o_value;

uniform sampler2D u_keys;
uniform sampler2D u_blur_intensity;
uniform sampler2D u_blur_diffuse;
uniform sampler2D u_blur_depth;
uniform sampler2D u_blur_edges;  // the blurred wet edges (the composite's fourth value per slot)

void main() {
  ivec2 size = textureSize(u_keys, 0);
  ivec2 q = ivec2(gl_FragCoord.xy);
  int part = q.x / size.x;
  ivec2 p = ivec2(q.x - part * size.x, q.y);
  if (part == 0) {
    vec4 k = texelFetch(u_keys, p, 0);
    bool same = all(equal(k, texelFetch(u_keys, list_clamp(p + ivec2(1, 0), size), 0))) &&
                all(equal(k, texelFetch(u_keys, list_clamp(p + ivec2(0, 1), size), 0))) &&
                all(equal(k, texelFetch(u_keys, list_clamp(p + ivec2(1, 1), size), 0)));
    o_value = same ? k : vec4(-1.0);
    return;
  }
  int slot = part - 1;
  o_value = vec4(texelFetch(u_blur_intensity, p, 0)[slot], texelFetch(u_blur_diffuse, p, 0)[slot],
                 texelFetch(u_blur_depth, p, 0)[slot], texelFetch(u_blur_edges, p, 0)[slot]);
}
