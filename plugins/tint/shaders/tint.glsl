// out = mix(colour, tint, amount); alpha is kept. amount 0 and 1 are exact because mix is
// evaluated as c + (t - c) * a only inside (0, 1).
//
// The node's per-pixel function (aq_pointwise_desc): its own pass and the host's fused passes
// both call it, with AQ_APPLY and AQ_UNIFORM defined by the caller.
uniform vec3 AQ_UNIFORM(tint);
uniform float AQ_UNIFORM(amount);

vec4 AQ_APPLY(vec4 c, vec2 pixel, vec2 size) {
  float amount = AQ_UNIFORM(amount);
  vec3 rgb = amount <= 0.0 ? c.rgb : (amount >= 1.0 ? AQ_UNIFORM(tint) : mix(c.rgb, AQ_UNIFORM(tint), amount));
  return vec4(rgb, c.a);
}
