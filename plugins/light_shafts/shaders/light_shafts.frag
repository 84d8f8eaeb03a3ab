// Light shafts in the water (README): the light the water between the camera and each surface
// scatters towards the eye where the caustics focus it. Along the view ray, N segments; at each
// segment's middle Q the light is followed back up to the water plane and the caustic texture
// read there (periodic bilinear, texelFetch); its excess over flat water, max(c - 1, 0), weighs
// the exact integral of sigma exp(-sigma t) over the segment.
uniform sampler2D u_image;
uniform sampler2D u_position;  // world xyz, alpha 1 where a surface is
uniform sampler2D u_caustics;  // one period of the caustic pattern, mean 1
uniform vec3 u_eye;
// The view ray of normalised device position ndc is forward + ndc.x * right + ndc.y * up (right
// and up scaled by the half field of view's tangent and the aspect on the CPU).
uniform vec3 u_forward;
uniform vec3 u_right;
uniform vec3 u_up;
uniform vec2 u_size;
uniform vec3 u_light_direction;  // where the light travels, unit, y < 0
uniform vec3 u_light_color;
uniform float u_water_height;
uniform float u_tile;  // world units per caustic period
uniform float u_strength;
uniform float u_extinction;  // sigma, per world unit
uniform float u_max_distance;
uniform int u_steps;

layout(location = 0) out vec4 o_color;

uniform vec2 u_caustic_size;  // the caustic texture's width and height, texels

// A column or row index wrapped into [0, n): float arithmetic (llvmpipe runs integer division
// lane by lane), with the quotient's rounding corrected by one period either way.
vec2 wrap_index(vec2 i, vec2 n) {
  vec2 r = i - n * floor(i / n);
  r -= n * vec2(greaterThanEqual(r, n));
  r += n * vec2(lessThan(r, vec2(0.0)));
  return r;
}

// The caustic texture at tile coordinates uv, wrapping: texel centres at (i + 1/2) / size.
vec3 caustic(vec2 uv) {
  vec2 a = uv * u_caustic_size - 0.5;
  vec2 cell = floor(a);
  vec2 f = a - cell;
  ivec2 i0 = ivec2(wrap_index(cell, u_caustic_size));
  ivec2 i1 = ivec2(wrap_index(cell + 1.0, u_caustic_size));
  vec3 b = mix(texelFetch(u_caustics, i0, 0).rgb, texelFetch(u_caustics, ivec2(i1.x, i0.y), 0).rgb,
               f.x);
  vec3 t = mix(texelFetch(u_caustics, ivec2(i0.x, i1.y), 0).rgb, texelFetch(u_caustics, i1, 0).rgb,
               f.x);
  return mix(b, t, f.y);
}

void main() {
  vec2 uv = gl_FragCoord.xy / u_size;
  // Nearest texels (a blend of two surfaces' positions is neither's).
  vec4 picture = texelFetch(u_image, ivec2(uv * vec2(textureSize(u_image, 0))), 0);
  vec4 surface = texelFetch(u_position, ivec2(uv * vec2(textureSize(u_position, 0))), 0);
  vec3 ray;
  float distance_to = u_max_distance;
  if (surface.a == 1.0) {
    vec3 to_surface = surface.xyz - u_eye;
    float length_to = length(to_surface);
    ray = length_to > 0.0 ? to_surface / length_to : u_forward;
    distance_to = min(length_to, u_max_distance);
  } else {
    vec2 ndc = 2.0 * uv - 1.0;
    ray = normalize(u_forward + ndc.x * u_right + ndc.y * u_up);
  }
  vec3 light = vec3(0.0);
  if (u_light_direction.y < 0.0 && distance_to > 0.0) {
    // Where the light through q = eye + t ray left the water plane is linear in t:
    // w.xz = w0 + t wd (README), so each step adds wd * step_length to the tile coordinates.
    float to_surface_per_unit = 1.0 / -u_light_direction.y;
    vec2 w0 = u_eye.xz - (u_water_height - u_eye.y) * to_surface_per_unit * u_light_direction.xz;
    vec2 wd = ray.xz + ray.y * to_surface_per_unit * u_light_direction.xz;
    float step_length = distance_to / float(u_steps);
    // exp(-sigma t) at the segment's ends, by a constant ratio per segment.
    float ratio = exp(-u_extinction * step_length);
    float near_weight = 1.0;
    for (int k = 0; k < u_steps; ++k) {
      float t = (float(k) + 0.5) * step_length;
      float far_weight = near_weight * ratio;
      if (u_eye.y + t * ray.y < u_water_height) {  // only water scatters
        vec3 excess = max(caustic((w0 + t * wd) / u_tile) - vec3(1.0), vec3(0.0));
        light += excess * (near_weight - far_weight);
      }
      near_weight = far_weight;
    }
  }
  o_color = vec4(picture.rgb + u_strength * u_light_color * light, picture.a);
}
