// Flat grey-scale and luminance-ordered morphology (erosion and dilation) shared by the `erode`
// and `dilate` plugins: `#define AQ_MORPH_DILATE` (or nothing, for erosion) before
// `#include "aquarelle/morphology.glsl"`. The file holds the whole fragment shader, main()
// included, so the two plugins run literally the same code with one define flipped.
//
// The footprint (a square or a disc of diameter `size`) is described as one horizontal span per
// row offset dy in [-r, r], with half-width w(dy). Because min and max are associative, the
// extreme over the footprint is the extreme, over dy, of the extreme over the row span of
// half-width w(dy). So the work is split in two passes whose cost grows with k, not k^2:
//
//   pass 0 (rows):    image ──► span_i(x, y) = extreme over |t| <= w_i of image(x + t, y)
//                               for each distinct half-width w_i (one MRT output each, <= 5)
//   pass 1 (columns): span_* ──► out(x, y) = extreme over dy of span_{row_span[dy]}(x, y + dy)
//
// A square has a single span (w_i = r), so pass 0 writes one texture and this is the classic
// separable min/max filter. Lookups clamp to the image (texelFetch of clamped coordinates), which
// for these footprints is the same as restricting the window to the image.
//
// Orders (u_mode): 0 = per channel (min/max of each of r, g, b, a separately, the seed's §3.3);
// 1 = luminance order (a total order on colours: Rec.709 luminance, ties broken by r, g, b, a),
// so every output pixel is one of the window's input colours and no new colour appears.

in vec2 v_uv;
layout(location = 0) out vec4 o_color;  // pass 1 result, or span 0 in pass 0
layout(location = 1) out vec4 o_span1;
layout(location = 2) out vec4 o_span2;
layout(location = 3) out vec4 o_span3;
layout(location = 4) out vec4 o_span4;

const int AQ_MORPH_MAX_RADIUS = 4;  // size 9
const int AQ_MORPH_MAX_SPANS = AQ_MORPH_MAX_RADIUS + 1;

uniform int u_pass;    // 0 rows, 1 columns
uniform int u_mode;    // 0 per channel, 1 luminance order
uniform int u_radius;  // r = (size - 1) / 2
// Pass 0 inputs.
uniform sampler2D u_image;
uniform int u_span_count;
uniform int u_span_half_width[AQ_MORPH_MAX_SPANS];  // ascending
// Pass 1 inputs.
uniform sampler2D u_spans[AQ_MORPH_MAX_SPANS];
uniform int u_row_span[2 * AQ_MORPH_MAX_RADIUS + 1];  // span index for dy = i - r

// True when colour a comes strictly before b in the luminance order.
bool aq_morph_luminance_less(vec4 a, vec4 b) {
  const vec3 weights = vec3(0.2126, 0.7152, 0.0722);
  float la = dot(a.rgb, weights);
  float lb = dot(b.rgb, weights);
  if (la != lb) return la < lb;
  if (a.r != b.r) return a.r < b.r;
  if (a.g != b.g) return a.g < b.g;
  if (a.b != b.b) return a.b < b.b;
  return a.a < b.a;
}

// Combines the running extreme with a candidate: min for erosion, max for dilation.
vec4 aq_morph_combine(vec4 best, vec4 candidate) {
#ifdef AQ_MORPH_DILATE
  if (u_mode == 1) return aq_morph_luminance_less(best, candidate) ? candidate : best;
  return max(best, candidate);
#else
  if (u_mode == 1) return aq_morph_luminance_less(candidate, best) ? candidate : best;
  return min(best, candidate);
#endif
}

vec4 aq_morph_fetch(sampler2D image, ivec2 p) {
  ivec2 last = textureSize(image, 0) - 1;
  return texelFetch(image, clamp(p, ivec2(0), last), 0);
}

void aq_morph_rows(ivec2 p) {
  vec4 spans[AQ_MORPH_MAX_SPANS];
  vec4 best = aq_morph_fetch(u_image, p);
  int next_span = 0;
  // Grow the span outwards one step at a time and record it when it reaches each half-width.
  for (int t = 0; t <= u_radius; ++t) {
    if (t > 0) {
      best = aq_morph_combine(best, aq_morph_fetch(u_image, p + ivec2(t, 0)));
      best = aq_morph_combine(best, aq_morph_fetch(u_image, p - ivec2(t, 0)));
    }
    while (next_span < u_span_count && u_span_half_width[next_span] == t) {
      spans[next_span] = best;
      ++next_span;
    }
  }
  o_color = spans[0];
  o_span1 = u_span_count > 1 ? spans[1] : spans[0];
  o_span2 = u_span_count > 2 ? spans[2] : spans[0];
  o_span3 = u_span_count > 3 ? spans[3] : spans[0];
  o_span4 = u_span_count > 4 ? spans[4] : spans[0];
}

void aq_morph_columns(ivec2 p) {
  vec4 best = aq_morph_fetch(u_spans[u_row_span[u_radius]], p);
  for (int dy = 1; dy <= u_radius; ++dy) {
    vec4 above = aq_morph_fetch(u_spans[u_row_span[u_radius + dy]], p + ivec2(0, dy));
    vec4 below = aq_morph_fetch(u_spans[u_row_span[u_radius - dy]], p - ivec2(0, dy));
    best = aq_morph_combine(aq_morph_combine(best, above), below);
  }
  o_color = best;
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  if (u_pass == 0) {
    aq_morph_rows(p);
  } else {
    aq_morph_columns(p);
  }
}
