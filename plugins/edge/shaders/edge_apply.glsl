// edge_apply's per-pixel function (aq_pointwise_desc): the colour at the pixel times
// mix(1, factor, w), w the darkening weight `edge_detect` wrote, read at the pixel under the
// output pixel's centre (so any size works). `edge` computes w in place of this one read.
// The node's own pass and the host's fused passes both call it.
uniform sampler2D AQ_UNIFORM(edges);
uniform float AQ_UNIFORM(factor);

vec4 AQ_APPLY(vec4 c, vec2 pixel, vec2 size) {
  ivec2 edges_size = textureSize(AQ_UNIFORM(edges), 0);
  ivec2 p = clamp(ivec2(floor(pixel / size * vec2(edges_size))), ivec2(0), edges_size - 1);
  float w = texelFetch(AQ_UNIFORM(edges), p, 0).r;
  return vec4(c.rgb * mix(1.0, AQ_UNIFORM(factor), w), c.a);
}
