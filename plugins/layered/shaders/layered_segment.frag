// Segmentation and layer lighting of four channels at once; a channel holds any number of
// objects far enough apart (layer_packing.h), the owner image says which one paints here:
//   mask_k    = [id == id of owner_k]
//   intensity = mask_k · (1 − step(specular_threshold, (n·h)^shininess))   highlights -> paper
//   diffuse   = intensity · clamp(n·l, 0, 1)        (premultiplied: the blur then averages it)
//   depth     = intensity · z                       (premultiplied likewise)
layout(location = 0) out vec4 o_intensity;
layout(location = 1) out vec4 o_diffuse;
layout(location = 2) out vec4 o_depth;

uniform sampler2D u_id;
uniform sampler2D u_normal;
uniform sampler2D u_depth;
uniform sampler2D u_owner;  // per channel: 1 + the layer painting here, 0 for none
uniform sampler2D u_table;  // row 0: (id, wet-in-wet) per layer
uniform vec3 u_light;  // unit vector towards the light
uniform vec3 u_half;   // unit Blinn-Phong half vector
uniform float u_shininess;
uniform float u_specular_threshold;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float id = texelFetch(u_id, p, 0).r;
  vec4 owner = texelFetch(u_owner, p, 0);
  vec4 ids = vec4(-1.0);
  for (int k = 0; k < 4; ++k) {
    if (owner[k] > 0.5) ids[k] = texelFetch(u_table, ivec2(int(owner[k]) - 1, 0), 0).r;
  }
  vec4 mask = vec4(equal(vec4(id), ids));  // NaN equals nothing
  vec3 n = texelFetch(u_normal, p, 0).xyz;
  float len = length(n);
  n = len > 1.0e-6 && len < 1.0e30 ? n / len : vec3(0.0);
  float diffuse = clamp(dot(n, u_light), 0.0, 1.0);
  float specular = pow(max(dot(n, u_half), 0.0), u_shininess);
  float highlight = specular >= u_specular_threshold ? 1.0 : 0.0;
  float z = texelFetch(u_depth, p, 0).r;
  z = z > 0.0 && z < 3.0e38 ? z : 0.0;
  vec4 intensity = mask * (1.0 - highlight);
  o_intensity = intensity;
  o_diffuse = intensity * diffuse;
  o_depth = intensity * z;
}
