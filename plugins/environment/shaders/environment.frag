// The environment behind the scene from an equirectangular panorama (README): each
// background pixel (id 0) looks along its view ray; longitude and latitude of the ray pick the
// panorama's texel, bilinearly, wrapping around in longitude and clamped at the poles.
uniform sampler2D u_image;
uniform sampler2D u_id;
uniform sampler2D u_panorama;
// The view ray of normalised device position ndc is forward + ndc.x * right + ndc.y * up
// (right and up scaled by the half field of view's tangent and the aspect on the CPU): no
// unprojection through the near and far planes, whose float rounding moved the ray by 1e-4 rad.
uniform vec3 u_forward;
uniform vec3 u_right;
uniform vec3 u_up;
uniform vec2 u_size;
uniform ivec2 u_panorama_size;
uniform float u_rotation;  // radians added to the longitude
uniform float u_intensity;

layout(location = 0) out vec4 o_color;

const float kPi = 3.14159265358979;

vec3 texel(int i, int j) {
  i = (i % u_panorama_size.x + u_panorama_size.x) % u_panorama_size.x;  // wraps in longitude
  j = clamp(j, 0, u_panorama_size.y - 1);                               // clamps at the poles
  return texelFetch(u_panorama, ivec2(i, j), 0).rgb;
}

void main() {
  vec4 colour = texelFetch(u_image, ivec2(gl_FragCoord.xy), 0);
  vec2 uv = gl_FragCoord.xy / u_size;
  if (round(texture(u_id, uv).r) != 0.0) {
    o_color = colour;
    return;
  }
  vec2 ndc = uv * 2.0 - 1.0;
  vec3 d = normalize(u_forward + ndc.x * u_right + ndc.y * u_up);
  // Longitude 0 looks along -z, growing towards +x; latitude from -pi/2 (down) to pi/2 (up).
  float longitude = atan(d.x, -d.z) + u_rotation;
  float latitude = asin(clamp(d.y, -1.0, 1.0));
  float u = fract(0.5 + longitude / (2.0 * kPi));
  float v = 0.5 + latitude / kPi;
  vec2 at = vec2(u, v) * vec2(u_panorama_size) - 0.5;
  ivec2 i0 = ivec2(floor(at));
  vec2 f = at - vec2(i0);
  vec3 bottom = mix(texel(i0.x, i0.y), texel(i0.x + 1, i0.y), f.x);
  vec3 top = mix(texel(i0.x, i0.y + 1), texel(i0.x + 1, i0.y + 1), f.x);
  o_color = vec4(u_intensity * mix(bottom, top, f.y), 1.0);
}
