// CPU reference of the g-buffer's albedo for textured objects, in double precision, written
// from the maths (not the shaders): a ray through each pixel centre (gluPerspective/lookAt
// camera) hits the nearest triangle that is not cut out; the albedo there is the
// barycentric-interpolated vertex colour times the base colour texture, sampled bilinearly
// with repeat wrapping (texel centres at (i + 0.5) / size, as GL_LINEAR magnification does),
// after sRGB 8-bit texels are decoded to linear with the IEC 61966-2-1 curve.
#pragma once

#include <glm/glm.hpp>

#include <optional>
#include <vector>

namespace aq::reference {

struct RefCamera {
  glm::dvec3 eye;
  glm::dvec3 target;
  double fov_y_degrees;
};

// Linear RGBA texels, row 0 at v = 0 (the bottom of the image).
struct RefTexture {
  int width = 0;
  int height = 0;
  std::vector<glm::dvec4> texels;
  glm::dvec4 at(int x, int y) const { return texels[static_cast<size_t>(y) * width + x]; }
};

struct RefTriangle {
  glm::dvec3 p[3];
  glm::dvec2 uv[3];
  glm::dvec3 color[3];
  const RefTexture* texture = nullptr;  // null: white
  double alpha_cutoff = 0.0;
};

// sRGB-encoded value in [0, 1] to linear.
double srgb_to_linear(double encoded);

glm::dvec4 sample_bilinear_repeat(const RefTexture& texture, const glm::dvec2& uv);

struct RefHit {
  glm::dvec3 albedo;
  double alpha = 1.0;   // the texture's alpha where it was hit
  size_t triangle = 0;  // index of the triangle hit
};

// The albedo seen through pixel (x, y) (row 0 at the bottom) of a width x height render at
// the sub-pixel offset (dx, dy) from its centre, or nullopt for the background.
std::optional<RefHit> reference_albedo(const std::vector<RefTriangle>& triangles,
                                       const RefCamera& camera, int width, int height, int x, int y,
                                       double dx = 0.0, double dy = 0.0);

}  // namespace aq::reference
