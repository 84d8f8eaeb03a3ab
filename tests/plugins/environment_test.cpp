// `environment` (issue 38: seed 001's skybox from an image file): every background pixel shows
// the equirectangular panorama along its view ray, bilinear, wrapping in longitude; object
// pixels keep the picture. Against a CPU reference written from the README's maths (pinhole
// camera, longitude atan2(x, -z), latitude asin(y)), with the hard cases: a 1x1 panorama (one
// colour everywhere) and a 16384-wide one (the widest texture the host guarantees).
#include <gtest/gtest.h>

#include <aquarelle/core/image_io.h>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <string>

#include "support/harness.h"

namespace {

namespace fs = std::filesystem;
using aq::ImageF;

constexpr int kSize = 64;
const glm::dvec3 kEye(0.3, 0.4, 2.5), kTarget(0.0, 0.3, 0.0);
constexpr double kFov = 70.0;

// A panorama of w x h texels whose colours vary smoothly and distinctly, as linear EXR.
ImageF panorama(int w, int h) {
  ImageF image(w, h, 4);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      image.at(x, y, 0) = static_cast<float>(0.5 + 0.5 * std::sin(6.283185307 * x / w));
      image.at(x, y, 1) = static_cast<float>((y + 0.5) / h);
      // Texel to texel steps test the bilinear weights; too fine for the widest one, where the
      // float ray's rounding (a few thousandths of a texel) would meet them.
      image.at(x, y, 2) = w <= 1024 ? static_cast<float>(((x * 7 + y * 3) % 11) / 10.0)
                                    : static_cast<float>(0.5 + 0.5 * std::cos(18.85 * x / w));
      image.at(x, y, 3) = 1.0f;
    }
  }
  return image;
}

// README: the view ray of pixel (x, y) (row 0 at the bottom), its longitude and latitude, the
// panorama's bilinear texel there (u wraps, v clamps), times `intensity`.
glm::dvec3 reference(const ImageF& pano, int x, int y, double rotation_degrees, double intensity) {
  const glm::dvec3 forward = glm::normalize(kTarget - kEye);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(0, 1, 0)));
  const glm::dvec3 up = glm::cross(right, forward);
  const double tan_half = std::tan(kFov * M_PI / 360.0);
  const double ndc_x = 2.0 * (x + 0.5) / kSize - 1.0, ndc_y = 2.0 * (y + 0.5) / kSize - 1.0;
  const glm::dvec3 d = glm::normalize(forward + ndc_x * tan_half * right + ndc_y * tan_half * up);
  const double longitude = std::atan2(d.x, -d.z) + rotation_degrees * M_PI / 180.0;
  double u = 0.5 + longitude / (2.0 * M_PI);
  u -= std::floor(u);
  const double v = 0.5 + std::asin(d.y) / M_PI;
  const double ax = u * pano.width - 0.5, ay = v * pano.height - 0.5;
  const int i0 = static_cast<int>(std::floor(ax)), j0 = static_cast<int>(std::floor(ay));
  const double fx = ax - i0, fy = ay - j0;
  auto texel = [&](int i, int j) {
    i = ((i % pano.width) + pano.width) % pano.width;
    j = std::clamp(j, 0, pano.height - 1);
    return glm::dvec3(pano.at(i, j, 0), pano.at(i, j, 1), pano.at(i, j, 2));
  };
  const glm::dvec3 bottom = glm::mix(texel(i0, j0), texel(i0 + 1, j0), fx);
  const glm::dvec3 top = glm::mix(texel(i0, j0 + 1), texel(i0 + 1, j0 + 1), fx);
  return intensity * glm::mix(bottom, top, fy);
}

nlohmann::json graph(const std::string& panorama_path, double rotation, double intensity) {
  return {{"aquarelle", 1},
          {"nodes",
           {{"cube", {{"type", "object"}, {"params", {{"source", "cube"}, {"id", 3}}}}},
            {"join",
             {{"type", "scene_join"},
              {"params",
               {{"camera_position", {kEye.x, kEye.y, kEye.z}},
                {"camera_target", {kTarget.x, kTarget.y, kTarget.z}},
                {"fov", kFov},
                {"environment", "none"}}},
              {"inputs", {{"objects", {"cube.object"}}}}}},
            {"gbuf", {{"type", "gbuffer"}, {"inputs", {{"scene", "join.scene"}}}}},
            {"pano", {{"type", "read"}, {"params", {{"path", panorama_path}}}}},
            {"env",
             {{"type", "environment"},
              {"params", {{"rotation", rotation}, {"intensity", intensity}}},
              {"inputs",
               {{"image", "gbuf.albedo"},
                {"id", "gbuf.id"},
                {"scene", "join.scene"},
                {"panorama", "pano.image"}}}}}}},
          {"output", "env.image"}};
}

ImageF render(const nlohmann::json& g, const std::string& output) {
  aq::test::RenderOptions options;
  options.width = options.height = kSize;
  options.output = output;
  auto image = aq::test::render_graph(g.dump(), options);
  EXPECT_TRUE(image.ok()) << (image.ok() ? "" : image.message());
  return image.ok() ? *image : ImageF();
}

struct Checked {
  double background_error = 0.0, object_error = 0.0;
  int background = 0, objects = 0;
};

Checked check(int w, int h, double rotation, double intensity) {
  const fs::path dir = fs::temp_directory_path() / ("aq_environment_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / ("pano_" + std::to_string(w) + "x" + std::to_string(h) + ".exr");
  const ImageF pano = panorama(w, h);
  aq::WriteOptions options;
  options.float_data = true;
  EXPECT_TRUE(aq::write_image(file.string(), pano, options).ok());
  const nlohmann::json g = graph(file.string(), rotation, intensity);
  const ImageF out = render(g, "env.image");
  const ImageF albedo = render(g, "gbuf.albedo");
  const ImageF id = render(g, "gbuf.id");
  Checked c;
  if (out.width != kSize || id.width != kSize) return c;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      if (id.at(x, y, 0) != 0.0f) {
        ++c.objects;
        for (int k = 0; k < 4; ++k) {
          c.object_error =
              std::max<double>(c.object_error, std::abs(out.at(x, y, k) - albedo.at(x, y, k)));
        }
        continue;
      }
      ++c.background;
      const glm::dvec3 expected = reference(pano, x, y, rotation, intensity);
      for (int k = 0; k < 3; ++k) {
        c.background_error = std::max(c.background_error, std::abs(out.at(x, y, k) - expected[k]));
      }
      c.background_error = std::max<double>(c.background_error, std::abs(out.at(x, y, 3) - 1.0));
    }
  }
  return c;
}

TEST(Environment, BackgroundShowsThePanoramaAlongTheViewRay) {
  const Checked c = check(256, 128, 0.0, 1.0);
  EXPECT_GT(c.background, kSize * kSize / 2);
  EXPECT_GT(c.objects, 50);
  EXPECT_EQ(c.object_error, 0.0) << "objects keep the picture exactly";
  // The blue channel steps by up to 1 from texel to texel, so the error is the lookup's position
  // error in texels: measured 0.007 on llvmpipe, whose atan and asin are accurate to about
  // 2e-4 rad (the ray itself to ~1e-7).
  EXPECT_LT(c.background_error, 0.01);
}

TEST(Environment, RotationAndIntensity) {
  const Checked c = check(256, 128, 75.0, 2.5);
  EXPECT_GT(c.background, kSize * kSize / 2);
  EXPECT_LT(c.background_error, 2.5 * 0.01);
}

TEST(Environment, OneTexelPanoramaIsOneColour) {
  const Checked c = check(1, 1, 0.0, 1.0);
  EXPECT_GT(c.background, kSize * kSize / 2);
  EXPECT_LT(c.background_error, 1e-6);
}

TEST(Environment, PanoramaSixteenThousandTexelsWide) {
  const Checked c = check(16384, 2, 30.0, 1.0);
  EXPECT_GT(c.background, kSize * kSize / 2);
  EXPECT_LT(c.background_error, 2e-3);
}

// --- Cube maps: six faces, one of them missing -------------------------------------------

// Face f of `size` texels: a colour of its own plus a texel ramp, as linear EXR.
ImageF cube_face(int f, int size) {
  ImageF image(size, size, 4);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      image.at(x, y, 0) = static_cast<float>(0.1 + 0.15 * f);
      image.at(x, y, 1) = static_cast<float>((x + 0.5) / size);
      image.at(x, y, 2) = static_cast<float>((y + 0.5) / size);
      image.at(x, y, 3) = 1.0f;
    }
  }
  return image;
}

// README: the face of d's largest component, (right, up) / |major| to [0, 1], bilinear with
// the face's texels clamped; a missing face gives `missing`.
glm::dvec3 cube_reference(const std::vector<ImageF>& faces, const std::vector<bool>& present,
                          const glm::dvec3& d, const glm::dvec3& missing) {
  const glm::dvec3 a = glm::abs(d);
  int f;
  glm::dvec2 p;
  if (a.x >= a.y && a.x >= a.z) {
    f = d.x > 0 ? 0 : 1;
    p = glm::dvec2(d.x > 0 ? d.z : -d.z, d.y) / a.x;
  } else if (a.y >= a.z) {
    f = d.y > 0 ? 2 : 3;
    p = glm::dvec2(d.x, d.y > 0 ? d.z : -d.z) / a.y;
  } else {
    f = d.z > 0 ? 4 : 5;
    p = glm::dvec2(d.z > 0 ? -d.x : d.x, d.y) / a.z;
  }
  if (!present[f]) return missing;
  const ImageF& face = faces[f];
  const double ax = (0.5 * p.x + 0.5) * face.width - 0.5,
               ay = (0.5 * p.y + 0.5) * face.height - 0.5;
  const int i0 = static_cast<int>(std::floor(ax)), j0 = static_cast<int>(std::floor(ay));
  const double fx = ax - i0, fy = ay - j0;
  auto texel = [&](int i, int j) {
    i = std::clamp(i, 0, face.width - 1), j = std::clamp(j, 0, face.height - 1);
    return glm::dvec3(face.at(i, j, 0), face.at(i, j, 1), face.at(i, j, 2));
  };
  return glm::mix(glm::mix(texel(i0, j0), texel(i0 + 1, j0), fx),
                  glm::mix(texel(i0, j0 + 1), texel(i0 + 1, j0 + 1), fx), fy);
}

// Renders the cube map seen from `eye` towards `target` (fov 100: several faces in view) with
// face `missing_face` not connected, and returns the largest error over the background and the
// number of background pixels that looked at the missing face.
std::pair<double, int> check_cube(const glm::dvec3& eye, const glm::dvec3& target,
                                  int missing_face) {
  const char* names[6] = {"cube_px", "cube_nx", "cube_py", "cube_ny", "cube_pz", "cube_nz"};
  const fs::path dir = fs::temp_directory_path() / ("aq_environment_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::vector<ImageF> faces;
  std::vector<bool> present;
  nlohmann::json g = graph("", 0.0, 1.0);
  g["nodes"].erase("pano");
  g["nodes"]["env"]["inputs"].erase("panorama");
  g["nodes"]["env"]["params"]["missing_face_color"] = {0.9, 0.05, 0.6};
  g["nodes"]["join"]["params"]["camera_position"] = {eye.x, eye.y, eye.z};
  g["nodes"]["join"]["params"]["camera_target"] = {target.x, target.y, target.z};
  g["nodes"]["join"]["params"]["fov"] = 100.0;
  for (int f = 0; f < 6; ++f) {
    faces.push_back(cube_face(f, 8));
    present.push_back(f != missing_face);
    if (f == missing_face) continue;
    const fs::path file = dir / (std::string(names[f]) + ".exr");
    aq::WriteOptions options;
    options.float_data = true;
    EXPECT_TRUE(aq::write_image(file.string(), faces.back(), options).ok());
    g["nodes"][names[f]] = {{"type", "read"}, {"params", {{"path", file.string()}}}};
    g["nodes"]["env"]["inputs"][names[f]] = std::string(names[f]) + ".image";
  }
  const ImageF out = render(g, "env.image");
  const ImageF id = render(g, "gbuf.id");
  if (out.width != kSize || id.width != kSize) return {1e9, 0};
  const glm::dvec3 forward = glm::normalize(target - eye);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(0, 1, 0)));
  const glm::dvec3 up = glm::cross(right, forward);
  const double tan_half = std::tan(100.0 * M_PI / 360.0);
  double error = 0.0;
  int at_missing = 0;
  const glm::dvec3 missing(0.9, 0.05, 0.6);
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      if (id.at(x, y, 0) != 0.0f) continue;
      const double nx = 2.0 * (x + 0.5) / kSize - 1.0, ny = 2.0 * (y + 0.5) / kSize - 1.0;
      const glm::dvec3 d = glm::normalize(forward + nx * tan_half * right + ny * tan_half * up);
      const glm::dvec3 expected = cube_reference(faces, present, d, missing);
      at_missing += expected == missing;
      for (int k = 0; k < 3; ++k) error = std::max(error, std::abs(out.at(x, y, k) - expected[k]));
    }
  }
  return {error, at_missing};
}

TEST(Environment, CubeMapWithAMissingFace) {
  // Looking down and sideways: the missing -y face, and +x, -z, -x around it.
  const auto [error, at_missing] = check_cube({0.2, 1.5, 1.0}, {0.6, -2.0, -0.5}, 3);
  EXPECT_GT(at_missing, 100) << "the missing face is in view";
  // Half-texel steps of an 8-texel face: a ray near a face's edge may pick the neighbour face
  // in float where double picks the other (tested over all pixels: the colours then differ).
  EXPECT_LT(error, 1e-3);
}

}  // namespace
