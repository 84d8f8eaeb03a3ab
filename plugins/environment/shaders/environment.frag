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
// Cube map mode (u_cube = 1): six faces +x, -x, +y, -y, +z, -z; a face not connected shows
// u_missing (its u_has_face is 0).
uniform int u_cube;
uniform sampler2D u_face0;
uniform sampler2D u_face1;
uniform sampler2D u_face2;
uniform sampler2D u_face3;
uniform sampler2D u_face4;
uniform sampler2D u_face5;
uniform int u_has_face[6];
uniform vec3 u_missing;

layout(location = 0) out vec4 o_color;

const float kPi = 3.14159265358979;

vec3 texel(int i, int j) {
  i = (i % u_panorama_size.x + u_panorama_size.x) % u_panorama_size.x;  // wraps in longitude
  j = clamp(j, 0, u_panorama_size.y - 1);                               // clamps at the poles
  return texelFetch(u_panorama, ivec2(i, j), 0).rgb;
}

// A texel of face f, clamped to the face (no filtering across faces). The face index varies per
// pixel, so each sampler is named, never indexed.
vec3 face_texel(int f, ivec2 t) {
  ivec2 size = f == 0 ? textureSize(u_face0, 0) : f == 1 ? textureSize(u_face1, 0)
             : f == 2 ? textureSize(u_face2, 0) : f == 3 ? textureSize(u_face3, 0)
             : f == 4 ? textureSize(u_face4, 0) : textureSize(u_face5, 0);
  t = clamp(t, ivec2(0), size - 1);
  if (f == 0) return texelFetch(u_face0, t, 0).rgb;
  if (f == 1) return texelFetch(u_face1, t, 0).rgb;
  if (f == 2) return texelFetch(u_face2, t, 0).rgb;
  if (f == 3) return texelFetch(u_face3, t, 0).rgb;
  if (f == 4) return texelFetch(u_face4, t, 0).rgb;
  return texelFetch(u_face5, t, 0).rgb;
}

ivec2 face_size(int f) {
  return f == 0 ? textureSize(u_face0, 0) : f == 1 ? textureSize(u_face1, 0)
       : f == 2 ? textureSize(u_face2, 0) : f == 3 ? textureSize(u_face3, 0)
       : f == 4 ? textureSize(u_face4, 0) : textureSize(u_face5, 0);
}

// The cube map along d (README): the face of the largest component; on it, the coordinates
// along the face's right and up directions divided by that component, to [0, 1].
vec3 cube_lookup(vec3 d) {
  vec3 a = abs(d);
  int f;
  vec2 p;  // (right, up) / major
  if (a.x >= a.y && a.x >= a.z) {
    f = d.x > 0.0 ? 0 : 1;
    p = vec2(d.x > 0.0 ? d.z : -d.z, d.y) / a.x;
  } else if (a.y >= a.z) {
    f = d.y > 0.0 ? 2 : 3;
    p = vec2(d.x, d.y > 0.0 ? d.z : -d.z) / a.y;
  } else {
    f = d.z > 0.0 ? 4 : 5;
    p = vec2(d.z > 0.0 ? -d.x : d.x, d.y) / a.z;
  }
  if (u_has_face[f] == 0) return u_missing;
  vec2 at = (0.5 * p + 0.5) * vec2(face_size(f)) - 0.5;
  ivec2 i0 = ivec2(floor(at));
  vec2 w = at - vec2(i0);
  vec3 bottom = mix(face_texel(f, i0), face_texel(f, i0 + ivec2(1, 0)), w.x);
  vec3 top = mix(face_texel(f, i0 + ivec2(0, 1)), face_texel(f, i0 + ivec2(1, 1)), w.x);
  return mix(bottom, top, w.y);
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
  if (u_cube == 1) {
    o_color = vec4(u_intensity * cube_lookup(d), 1.0);
    return;
  }
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
