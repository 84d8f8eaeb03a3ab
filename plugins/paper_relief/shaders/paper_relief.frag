// Paper relief (plugins/paper_relief/README.md): the painted image, with the paper colour showing
// through diluted areas, lit as a bump map by the paper height's central-difference normal:
//   base  = mix(C, paper_colour, clamp(show · m, 0, 1))
//   N     = normalize(−bump · ∂h/∂x, −bump · ∂h/∂y, 1),  s = max(N·L, 0) / L.z
//   out   = base · (1 + relief · (s − 1))        flat paper: s = 1 exactly, out = base
in vec2 v_uv;
out vec4 o_color;

uniform sampler2D u_image;
uniform sampler2D u_paper;  // height in r
uniform sampler2D u_mask;   // how much paper shows, in r
uniform int u_has_mask;
uniform vec3 u_light;       // unit, towards the light, z > 0
uniform vec3 u_paper_color;
uniform float u_bump;
uniform float u_relief;
uniform float u_show;

float height(ivec2 q) {
  ivec2 size = textureSize(u_paper, 0);
  return texelFetch(u_paper, clamp(q, ivec2(0), size - 1), 0).r;
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 image_size = textureSize(u_image, 0);
  vec4 c = texelFetch(u_image, p, 0);
  vec3 base = c.rgb;
  if (u_has_mask != 0) {
    ivec2 size = textureSize(u_mask, 0);
    float m = texelFetch(u_mask, min(p * size / image_size, size - 1), 0).r;
    if (isnan(m)) m = 0.0;
    float show = clamp(u_show * m, 0.0, 1.0);
    if (show > 0.0) base = mix(base, u_paper_color, show);
  }
  ivec2 q = p * textureSize(u_paper, 0) / image_size;
  float dx = 0.5 * (height(q + ivec2(1, 0)) - height(q - ivec2(1, 0)));
  float dy = 0.5 * (height(q + ivec2(0, 1)) - height(q - ivec2(0, 1)));
  if (isnan(dx) || isinf(dx)) dx = 0.0;
  if (isnan(dy) || isinf(dy)) dy = 0.0;
  vec3 n = normalize(vec3(-u_bump * dx, -u_bump * dy, 1.0));
  // Flat paper is exactly unlit (s = 1), whatever the division's rounding.
  float s = dx == 0.0 && dy == 0.0 ? 1.0 : max(dot(n, u_light), 0.0) / u_light.z;
  o_color = vec4(s == 1.0 ? base : base * (1.0 + u_relief * (s - 1.0)), c.a);
}
