// Pass 3 of `caustics`: copies the accumulated intensity into the output's working format,
// scaled by the energy normalisation factor (1 when normalisation is off), with alpha 1.
uniform sampler2D u_accumulated;
uniform float u_scale;

in vec2 v_uv;
layout(location = 0) out vec4 o_color;

void main() {
  vec3 intensity = texelFetch(u_accumulated, ivec2(gl_FragCoord.xy), 0).rgb;
  o_color = vec4(intensity * u_scale, 1.0);
}
