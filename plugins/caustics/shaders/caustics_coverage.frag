// Pass 2 of `caustics` with the `coverage` estimator: one fragment per grid cell. Each of the
// cell's two refracted triangles carries its original area's light (u_flux counts, fixed
// point) and shares it among the texels it overlaps in proportion to the exact area of overlap
// (an exact box filter of the piecewise-linear refraction map), added with integer atomics into
// u_counts, wrapped around the tile. The counts given out sum to exactly u_flux per triangle
// whatever the rounding, so the light is conserved by construction; a folded triangle is
// clipped like any other (its light stays positive) and a degenerate one gives all its light
// to the texel holding it. With u_identity the undisplaced grid is deposited instead: the
// counts flat water gives, which the resolve subtracts so that flat water is exactly 1.
uniform sampler2D u_displacement;  // u_grid x u_grid, rg = displacement in tile widths
uniform int u_grid;                // grid cells per tile side
uniform int u_resolution;          // texels per tile side
uniform uint u_flux;               // counts of light per triangle
uniform bool u_identity;           // deposit the undisplaced grid
layout(r32ui, binding = 0) uniform coherent uimage2D u_counts;

layout(location = 0) out vec4 o_color;

// Integer division and remainder are not SIMD instructions on the CPU (llvmpipe runs each
// lane's alone, and they dominated this pass): aq_floor_divide takes the quotient in float and
// corrects it.
#include "aquarelle/integer_division.glsl"

// Floor displacement of grid vertex v (0 <= v <= u_grid) in texels; the grid is periodic.
vec2 displacement_of(ivec2 v) {
  if (u_identity) return vec2(0.0);
  ivec2 wrapped = v - ivec2(greaterThanEqual(v, ivec2(u_grid))) * u_grid;
  return float(u_resolution) * texelFetch(u_displacement, wrapped, 0).xy;
}

int wrap_texel(int i) { return i - aq_floor_divide(i, u_resolution) * u_resolution; }

void add_light(ivec2 texel, uint counts) {
  if (counts != 0u) {
    imageAtomicAdd(u_counts, ivec2(wrap_texel(texel.x), wrap_texel(texel.y)), counts);
  }
}

// Mean of clamp(y, 0, 1) along a segment whose y runs linearly from y0 to y1: the fractions
// of the segment below 0 and above 1, and the mean of the part in between. Branch-free (the
// lanes of a SIMD shader take every branch anyway).
float mean_clamped(float y0, float y1) {
  float lo = min(y0, y1), hi = max(y0, y1);
  float span = max(hi - lo, 1e-30);
  float below = clamp(-lo / span, 0.0, 1.0);
  float above = clamp((hi - 1.0) / span, 0.0, 1.0);
  return above + (1.0 - below - above) * 0.5 * (clamp(lo, 0.0, 1.0) + clamp(hi, 0.0, 1.0));
}

// The integral of clamp(y, 0, 1) dx along the edge p -> q over its part in 0 <= x <= 1.
// Summed over a closed polygon's edges it is minus its signed area inside the unit square
// (Green's theorem with the square's indicator). `dydx` is the edge's slope (0 if vertical).
float edge_integral(vec2 p, vec2 q, float dydx) {
  float x0 = clamp(p.x, 0.0, 1.0), x1 = clamp(q.x, 0.0, 1.0);
  return (x1 - x0) * mean_clamped(p.y + (x0 - p.x) * dydx, p.y + (x1 - p.x) * dydx);
}

// The integrals along p -> q of y dx over x <= 1 (a half-plane's part of the signed area),
// and of min(y, 1) dx over x <= 1 (the quadrant x <= 1, y <= 1).
float half_plane_integral(vec2 p, vec2 q, float dydx) {
  float x0 = min(p.x, 1.0), x1 = min(q.x, 1.0);
  float y0 = p.y + (x0 - p.x) * dydx, y1 = p.y + (x1 - p.x) * dydx;
  return (x1 - x0) * 0.5 * (y0 + y1);
}
float quadrant_integral(vec2 p, vec2 q, float dydx) {
  float x0 = min(p.x, 1.0), x1 = min(q.x, 1.0);
  float y0 = p.y + (x0 - p.x) * dydx, y1 = p.y + (x1 - p.x) * dydx;
  float lo = min(y0, y1), hi = max(y0, y1);
  float above = clamp((hi - 1.0) / max(hi - lo, 1e-30), 0.0, 1.0);
  return (x1 - x0) * (above + (1.0 - above) * 0.5 * (min(lo, 1.0) + min(hi, 1.0)));
}

float slope(vec2 p, vec2 q) {
  float dx = q.x - p.x;
  return dx != 0.0 ? (q.y - p.y) / dx : 0.0;
}

// Texels per side of the window whose overlaps come in closed form (caustics.cpp defines it:
// 3 by default, 2 with `window` 2); a triangle spanning more texels goes texel by texel.
#ifndef AQ_WINDOW
#define AQ_WINDOW 3
#endif
const int kWindow = AQ_WINDOW;
const int kWindowTexels = AQ_WINDOW * AQ_WINDOW;

// Shares u_flux counts of the triangle abc (texel units, relative to texel `base`) among the
// texels it overlaps. A triangle within kWindow x kWindow texels returns true with its counts
// for the texels origin + (i, j), at index i + kWindow j, for the caller to add (the cell's
// two triangles mostly share the window: one set of atomics for both); a larger one adds its
// own.
bool deposit(ivec2 base, vec2 a, vec2 b, vec2 c, out ivec2 origin, out uint counts[kWindowTexels]) {
  vec2 lo_corner = floor(min(a, min(b, c)));
  ivec2 extent = ivec2(floor(max(a, max(b, c))) - lo_corner);
  origin = base + ivec2(lo_corner);
  for (int k = 0; k < kWindowTexels; ++k) counts[k] = 0u;
  a -= lo_corner;
  b -= lo_corner;
  c -= lo_corner;
  vec2 ab = b - a, ac = c - a;
  float area = 0.5 * abs(ab.x * ac.y - ab.y * ac.x);
  if (extent == ivec2(0) || !(area > 0.0)) {
    origin += ivec2(floor((a + b + c) / 3.0));
    counts[0] = u_flux;
    return true;
  }
  // Running total of the covered area: texel k gets round(Q · covered_k / area) minus what
  // the texels before it got, so the counts never go negative and add up to Q.
  float share = float(u_flux) / area;
  float ab_slope = slope(a, b), bc_slope = slope(b, c), ca_slope = slope(c, a);
  if (extent.x < kWindow && extent.y < kWindow) {
    // Within the window (nearly every triangle when the grid is about as fine as the texture;
    // a window of 2 leaves the stretched ones of the focal lines to the texel-by-texel loop,
    // which every SIMD lane then runs). C(X, Y), the area left of x = X and below y = Y, comes
    // from the areas left of x = X (L, a half plane), below y = Y (B, the same with x and y
    // swapped) and in the quadrant left of and below both (Q), each shifted to the unit lines;
    // the overlap of texel (i, j) is C's inclusion-exclusion over its four corners.
    float cumulative[(kWindow + 1) * (kWindow + 1)];  // C(X, Y) at X + (kWindow + 1) Y
    for (int k = 0; k < (kWindow + 1) * (kWindow + 1); ++k) cumulative[k] = 0.0;
    cumulative[kWindow + (kWindow + 1) * kWindow] = area;
    for (int line = 1; line < kWindow; ++line) {
      vec2 shift = vec2(float(line - 1));
      vec2 sa = a - shift, sb = b - shift, sc = c - shift;
      cumulative[line + (kWindow + 1) * kWindow] =
          abs(half_plane_integral(sa, sb, ab_slope) + half_plane_integral(sb, sc, bc_slope) +
              half_plane_integral(sc, sa, ca_slope));
      cumulative[kWindow + (kWindow + 1) * line] =
          abs(half_plane_integral(sa.yx, sb.yx, slope(a.yx, b.yx)) +
              half_plane_integral(sb.yx, sc.yx, slope(b.yx, c.yx)) +
              half_plane_integral(sc.yx, sa.yx, slope(c.yx, a.yx)));
      for (int other = 1; other < kWindow; ++other) {
        // Q at (X, Y) = (line, other).
        vec2 q = vec2(float(line - 1), float(other - 1));
        vec2 qa = a - q, qb = b - q, qc = c - q;
        cumulative[line + (kWindow + 1) * other] =
            abs(quadrant_integral(qa, qb, ab_slope) + quadrant_integral(qb, qc, bc_slope) +
                quadrant_integral(qc, qa, ca_slope));
      }
    }
    float covered = 0.0;
    uint given = 0u;
    for (int j = 0; j < kWindow; ++j) {
      for (int i = 0; i < kWindow; ++i) {
        float overlap = cumulative[(i + 1) + (kWindow + 1) * (j + 1)] -
                        cumulative[i + (kWindow + 1) * (j + 1)] -
                        cumulative[(i + 1) + (kWindow + 1) * j] + cumulative[i + (kWindow + 1) * j];
        covered += max(overlap, 0.0);
        uint upto = min(uint(round(covered * share)), u_flux);
        counts[i + kWindow * j] = upto - given;
        given = upto;
      }
    }
    // The rounding's remainder to the texel holding the centroid (inside the triangle, so
    // overlapped), selected without indexing by a variable (slow on SIMD lanes).
    ivec2 middle = ivec2(floor((a + b + c) / 3.0));
    for (int k = 0; k < kWindowTexels; ++k) {
      counts[k] += k == middle.x + kWindow * middle.y ? u_flux - given : 0u;
    }
    return true;
  }
  float covered = 0.0;
  uint given = 0u;
  ivec2 pending_texel = ivec2(0);
  uint pending = 0u;
  bool any = false;
  for (int y = 0; y <= extent.y; ++y) {
    for (int x = 0; x <= extent.x; ++x) {
      vec2 o = vec2(x, y);
      float overlap = abs(edge_integral(a - o, b - o, ab_slope) +
                          edge_integral(b - o, c - o, bc_slope) +
                          edge_integral(c - o, a - o, ca_slope));
      if (!(overlap > 0.0)) continue;
      covered += overlap;
      uint upto = min(uint(round(covered * share)), u_flux);
      if (any) add_light(pending_texel, pending);
      pending_texel = origin + ivec2(x, y);
      pending = upto - given;
      given = upto;
      any = true;
    }
  }
  if (!any) {
    origin += ivec2(floor((a + b + c) / 3.0));
    counts[0] = u_flux;
    return true;
  }
  add_light(pending_texel, pending + (u_flux - given));  // rounding's remainder
  return false;
}

void add_window(ivec2 origin, uint counts[kWindowTexels]) {
  for (int k = 0; k < kWindowTexels; ++k) {
    add_light(origin + ivec2(k % kWindow, k / kWindow), counts[k]);
  }
}

void main() {
  ivec2 cell = ivec2(gl_FragCoord.xy);
  // Positions relative to the texel `base` holding the cell's corner, so that the floats stay
  // small whatever the texture size.
  ivec2 scaled = cell * u_resolution;
  ivec2 base = aq_floor_divide(scaled, ivec2(u_grid));
  vec2 corner = vec2(scaled - base * u_grid) / float(u_grid);
  float texels_per_cell = float(u_resolution) / float(u_grid);
  vec2 p00 = corner + displacement_of(cell);
  vec2 p10 = corner + vec2(texels_per_cell, 0.0) + displacement_of(cell + ivec2(1, 0));
  vec2 p11 = corner + vec2(texels_per_cell) + displacement_of(cell + ivec2(1, 1));
  vec2 p01 = corner + vec2(0.0, texels_per_cell) + displacement_of(cell + ivec2(0, 1));
  vec4 xs = vec4(p00.x, p10.x, p11.x, p01.x), ys = vec4(p00.y, p10.y, p11.y, p01.y);
  if (any(isnan(xs)) || any(isinf(xs)) || any(isnan(ys)) || any(isinf(ys))) {
    add_light(base, 2u * u_flux);  // cannot happen for eta <= 1; keeps the light if it did
    o_color = vec4(0.0);
    return;
  }
  ivec2 first_origin, second_origin;
  uint first[kWindowTexels], second[kWindowTexels];
  bool first_windowed = deposit(base, p00, p10, p11, first_origin, first);
  bool second_windowed = deposit(base, p00, p11, p01, second_origin, second);
  if (first_windowed && second_windowed && first_origin == second_origin) {
    for (int k = 0; k < kWindowTexels; ++k) first[k] += second[k];
    add_window(first_origin, first);
  } else {
    if (first_windowed) add_window(first_origin, first);
    if (second_windowed) add_window(second_origin, second);
  }
  o_color = vec4(0.0);
}
