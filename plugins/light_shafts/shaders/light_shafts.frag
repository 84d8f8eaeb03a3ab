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

vec3 caustic_texel(ivec2 t, ivec2 size) {
  return texelFetch(u_caustics, (t % size + size) % size, 0).rgb;
}

// The caustic texture at tile coordinates uv, wrapping: texel centres at (i + 1/2) / size.
vec3 caustic(vec2 uv) {
  ivec2 size = textureSize(u_caustics, 0);
  vec2 a = uv * vec2(size) - 0.5;
  vec2 cell = floor(a);
  vec2 f = a - cell;
  // The cell index wraps before it becomes an integer: far from the origin a float's integer
  // part is exact, and the period of the texture keeps indices small.
  ivec2 i = ivec2(cell - vec2(size) * floor(cell / vec2(size)));
  vec3 b = mix(caustic_texel(i, size), caustic_texel(i + ivec2(1, 0), size), f.x);
  vec3 t = mix(caustic_texel(i + ivec2(0, 1), size), caustic_texel(i + ivec2(1, 1), size), f.x);
  return mix(b, t, f.y);
}

// What the caustics add to the light at q: the texture where the light through q left the
// water plane, over flat water's 1; nothing above the water.
vec3 excess(vec3 q) {
  if (q.y >= u_water_height) return vec3(0.0);
  float up = (u_water_height - q.y) / -u_light_direction.y;
  vec3 w = q - up * u_light_direction;
  return max(caustic(w.xz / u_tile) - vec3(1.0), vec3(0.0));
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
    float step_length = distance_to / float(u_steps);
    float near_weight = 1.0;  // exp(-sigma t) at the segment's near end
    for (int k = 0; k < u_steps; ++k) {
      float far_weight = exp(-u_extinction * step_length * float(k + 1));
      vec3 q = u_eye + (float(k) + 0.5) * step_length * ray;
      light += excess(q) * (near_weight - far_weight);
      near_weight = far_weight;
    }
  }
  o_color = vec4(picture.rgb + u_strength * u_light_color * light, picture.a);
}
