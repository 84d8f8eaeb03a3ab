// Pass 2 of `caustics`: draws the refracted grid, 6 vertices (2 triangles) per cell, no vertex
// buffer. Each vertex fetches its triangle's three refracted corners and passes the triangle's
// intensity, original area / refracted area, as a flat value. One draw covers a rectangle of
// cells, shifted by whole tiles (u_shift), so that triangles refracted across an edge of the
// tile reappear on the opposite side (the texture wraps, nothing is left unrendered); the host
// side draws only the cells of each shifted copy that can reach the tile.
uniform sampler2D u_displacement;  // u_grid x u_grid, rg = displacement in tile widths
uniform int u_grid;
uniform ivec2 u_first_cell;     // the rectangle of cells this draw covers
uniform int u_columns;
uniform ivec2 u_shift;          // copy offset in whole tiles
uniform float u_max_intensity;  // clamp of a triangle's intensity (degenerate triangles)

flat out float v_intensity;

const ivec2 kCorner[6] = ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 0), ivec2(1, 1),
                                  ivec2(0, 1));

// Displacement of grid vertex v in grid cells; the grid is periodic, vertex u_grid is vertex 0.
vec2 displacement_of(ivec2 v) {
  return float(u_grid) * texelFetch(u_displacement, v % u_grid, 0).xy;
}

void main() {
  int cell_index = gl_VertexID / 6;
  int corner = gl_VertexID % 6;
  int first = corner < 3 ? 0 : 3;
  ivec2 cell = u_first_cell + ivec2(cell_index % u_columns, cell_index / u_columns);

  ivec2 v0 = cell + kCorner[first];
  ivec2 v1 = cell + kCorner[first + 1];
  ivec2 v2 = cell + kCorner[first + 2];
  vec2 d0 = displacement_of(v0);
  vec2 d1 = displacement_of(v1);
  vec2 d2 = displacement_of(v2);
  // Edges in grid cells; the original triangle has doubled area 1, so the intensity is
  // 1 / |doubled refracted area|, exactly 1 for flat water. Folded triangles (negative area)
  // count with their absolute area; the clamp bounds degenerate ones.
  vec2 e1 = vec2(v1 - v0) + (d1 - d0);
  vec2 e2 = vec2(v2 - v0) + (d2 - d0);
  float doubled_area = abs(e1.x * e2.y - e1.y * e2.x);
  v_intensity = 1.0 / max(doubled_area, 1.0 / u_max_intensity);

  // Integer part first, then the displacement: a vertex shared by two copies gets bit-identical
  // coordinates in both, so the rasterizer's tie rule leaves no crack and no double cover.
  ivec2 v = cell + kCorner[corner];
  vec2 position = vec2(v + u_shift * u_grid) + displacement_of(v);
  gl_Position = vec4(position * (2.0 / float(u_grid)) - 1.0, 0.0, 1.0);
}
