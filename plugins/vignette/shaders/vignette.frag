// Radial darkening (seed §5.2), aspect-correct: distances are measured in pixels divided by
// the shorter side, so circles stay circles on any image shape and a square image matches the
// seed's `length(uv - 0.5)` exactly. Alpha is kept.
in vec2 v_uv;
layout(location = 0) out vec4 o_color;

uniform sampler2D u_image;
uniform vec2 u_size;      // image size in pixels
uniform float u_radius;   // darkening starts here (shorter side = 1)
uniform float u_ramp;     // distance over which it reaches full strength; 0: a hard step
uniform float u_strength; // darkening at full strength (the seed's 0.7)

void main() {
  vec4 c = texelFetch(u_image, ivec2(gl_FragCoord.xy), 0);
  // gl_FragCoord is at the pixel centre, so this matches the reference's (x + 0.5).
  float d = length((gl_FragCoord.xy - 0.5 * u_size) / min(u_size.x, u_size.y));
  float t = 0.0;
  if (d > u_radius) t = u_ramp > 0.0 ? min((d - u_radius) / u_ramp, 1.0) : 1.0;
  o_color = vec4(c.rgb * (1.0 - u_strength * t), c.a);
}
