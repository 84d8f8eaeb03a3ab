// The OpenColorIO display/view transform (working space -> display, e.g. sRGB "Standard"),
// applied on the GPU through OCIO's GLSL shader generator, with a CPU twin for tests and for
// images that never reach the GPU. The output node runs it before writing PNG/JPEG/TIFF.
//
// Alpha: the input is working-space colour with associated (premultiplied) alpha, as every
// node produces it; colour is divided by alpha (where alpha > 0) before the view, because a
// view is defined on straight colour. The output is display-referred with STRAIGHT alpha,
// which is what write_image stores in PNG/JPEG/TIFF. With alpha = 1 this changes nothing.
#pragma once

#include <aquarelle/core/color.h>
#include <aquarelle/core/gl_objects.h>
#include <aquarelle/core/image.h>
#include <aquarelle/core/result.h>

#include <memory>
#include <string>

namespace aq {

struct DisplayTransformData;

class DisplayTransform {
 public:
  // `display`/`view` empty: the config's defaults. An unknown display or view is an error
  // listing the available ones.
  static Result<DisplayTransform> create(const ColorConfig& config, const std::string& display,
                                         const std::string& view);

  const std::string& display() const;
  const std::string& view() const;

  // Needs a current GL 4.5 core context with the core's glad loaded. Renders `source_texture`
  // (a GL_TEXTURE_2D of width x height) through the transform into a new RGBA32F texture.
  // The compiled program and LUT textures are cached for the context current at the first
  // call; call release_gl() (with that context current) before using another context.
  Result<gl::Texture> apply(GLuint source_texture, int width, int height) const;
  void release_gl() const;

  // The same transform on the CPU, in place (RGB; alpha untouched).
  Status apply_cpu(ImageF& image) const;

  // The GLSL the GPU path compiles (for error messages and tests).
  const std::string& shader_source() const;

 private:
  explicit DisplayTransform(std::shared_ptr<DisplayTransformData> data) : data_(std::move(data)) {}
  std::shared_ptr<DisplayTransformData> data_;
};

}  // namespace aq
