// Pass 2 of `caustics`: every refracted triangle adds its intensity (blending ONE, ONE), so
// overlapping folded triangles add up.
flat in float v_intensity;

layout(location = 0) out vec4 o_color;

void main() { o_color = vec4(vec3(v_intensity), 0.0); }
