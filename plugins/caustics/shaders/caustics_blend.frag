// The seed's murky water (Coleman & Dodson): caustic images at successive times mixed with
// weights normalised to sum 1 (so the tile's mean stays 1), plus a per-channel shift (the
// seed's blue shift, (0, 0.05, 0.1)). Images past `u_count` are bound but weighted 0.
uniform sampler2D u_images[5];
uniform float u_weights[5];
uniform vec3 u_shift;

layout(location = 0) out vec4 o_color;

void main() {
  ivec2 texel = ivec2(gl_FragCoord.xy);
  // Σ w_k image_k with Σ w_k = 1, written as image_0 + Σ w_k (image_k - image_0): flat water
  // (every image exactly 1) stays exactly 1 whatever the weights round to.
  vec3 first = texelFetch(u_images[0], texel, 0).rgb;
  vec3 sum = first;
  for (int k = 1; k < 5; ++k) sum += u_weights[k] * (texelFetch(u_images[k], texel, 0).rgb - first);
  o_color = vec4(max(sum + u_shift, vec3(0.0)), 1.0);
}
