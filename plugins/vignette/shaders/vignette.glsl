// Radial darkening (seed §5.2), aspect-correct: distances are measured in pixels divided by
// the shorter side, so circles stay circles on any image shape and a square image matches the
// seed's `length(uv - 0.5)` exactly. Alpha is kept.
//
// The node's per-pixel function (aq_pointwise_desc): its own pass and the host's fused passes
// both call it, with AQ_APPLY and AQ_UNIFORM defined by the caller. The ramp is given relative
// to the shorter side, so the function is the same at any size the pass runs at.
uniform float AQ_UNIFORM(radius);   // darkening starts here (shorter side = 1)
uniform float AQ_UNIFORM(ramp);     // distance over which it reaches full strength; 0: a step
uniform float AQ_UNIFORM(strength); // darkening at full strength (the seed's 0.7)

vec4 AQ_APPLY(vec4 c, vec2 pixel, vec2 size) {
  // `pixel` is at the pixel centre, so this matches the reference's (x + 0.5).
  float d = length((pixel - 0.5 * size) / min(size.x, size.y));
  float radius = AQ_UNIFORM(radius);
  float ramp = AQ_UNIFORM(ramp);
  float t = 0.0;
  if (d > radius) t = ramp > 0.0 ? min((d - radius) / ramp, 1.0) : 1.0;
  return vec4(c.rgb * (1.0 - AQ_UNIFORM(strength) * t), c.a);
}
