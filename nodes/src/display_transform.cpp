// The OCIO display/view transform on the GPU and the CPU. OCIO's shader generator gives a
// GLSL function plus the LUT textures and uniforms it needs; this file wraps the function in
// a full-screen pass, uploads the LUTs, sets the uniforms, and caches the program per context.
// Input pixels are working-space linear with associated alpha; colour is un-premultiplied
// before the view (a view is defined on straight colour), so the output is display-referred
// with straight alpha, which is what PNG/JPEG/TIFF store.
#include <aquarelle/core/display_transform.h>

#include "color_config_data.h"

#include <glad/gl.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <vector>

namespace aq {
namespace {

constexpr const char* kFunctionName = "aq_ocio_display";
constexpr const char* kResourcePrefix = "aq_ocio_";

constexpr const char* kVertexShader = R"(#version 450 core
// One triangle that covers the viewport: vertices (-1,-1), (3,-1), (-1,3).
void main() {
  vec2 corner = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
)";

constexpr const char* kFragmentMain = R"(
uniform sampler2D aq_display_source;
layout(location = 0) out vec4 o_color;
void main() {
  vec4 color = texelFetch(aq_display_source, ivec2(gl_FragCoord.xy), 0);
  if (color.a > 0.0) color.rgb /= color.a;
  o_color = aq_ocio_display(color);
}
)";

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "\"" : ", \"") + item + "\"";
  return out;
}

bool contains(const std::vector<std::string>& items, const std::string& item) {
  for (const auto& candidate : items) {
    if (candidate == item) return true;
  }
  return false;
}

struct LutTexture {
  GLenum target = GL_TEXTURE_2D;
  std::string sampler;
  gl::Texture texture;
};

struct UniformBinding {
  GLint location = -1;
  OCIO::GpuShaderDesc::UniformData data;
};

struct GlState {
  gl::Program program;
  gl::VertexArray vertex_array;
  GLint source_location = -1;
  std::vector<LutTexture> luts;
  std::vector<UniformBinding> uniforms;
};

}  // namespace

struct DisplayTransformData {
  std::shared_ptr<const ColorConfigData> config;
  std::string display;
  std::string view;
  OCIO::ConstCPUProcessorRcPtr cpu;
  OCIO::GpuShaderDescRcPtr shader_desc;
  std::string fragment_source;
  mutable std::unique_ptr<GlState> gl;  // built at the first apply(), per GL context
};

namespace {

Result<gl::Shader> compile(GLenum stage, const std::string& source, const std::string& what) {
  gl::Shader shader(glCreateShader(stage));
  const char* text = source.c_str();
  glShaderSource(shader.get(), 1, &text, nullptr);
  glCompileShader(shader.get());
  GLint ok = GL_FALSE;
  glGetShaderiv(shader.get(), GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint length = 0;
    glGetShaderiv(shader.get(), GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
    glGetShaderInfoLog(shader.get(), length, nullptr, log.data());
    return make_error("display transform: the " + what + " shader does not compile (is a GL " +
                      "4.5 context current?): " + log.c_str());
  }
  return shader;
}

GLint filter_for(OCIO::Interpolation interpolation) {
  // Tetrahedral interpolation is done in the shader from nearest samples.
  return interpolation == OCIO::INTERP_NEAREST || interpolation == OCIO::INTERP_TETRAHEDRAL
             ? GL_NEAREST
             : GL_LINEAR;
}

void set_sampling(GLenum target, GLint filter) {
  glTexParameteri(target, GL_TEXTURE_MIN_FILTER, filter);
  glTexParameteri(target, GL_TEXTURE_MAG_FILTER, filter);
  glTexParameteri(target, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(target, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(target, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
}

// OCIO declares a LUT with height 1 as sampler1D, taller ones as sampler2D; read which one the
// generated code uses rather than relying on the rule of one OCIO version.
GLenum lut_target(const std::string& shader_text, const std::string& sampler) {
  return shader_text.find("sampler1D " + sampler) != std::string::npos ? GL_TEXTURE_1D
                                                                       : GL_TEXTURE_2D;
}

Status upload_luts(const DisplayTransformData& data, GlState& state) {
  const auto& desc = *data.shader_desc;
  const std::string text = desc.getShaderText();
  GLint previous_alignment = 4;
  glGetIntegerv(GL_UNPACK_ALIGNMENT, &previous_alignment);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (unsigned i = 0; i < desc.getNumTextures(); ++i) {
    const char* texture_name = nullptr;
    const char* sampler_name = nullptr;
    unsigned width = 0, height = 0;
    OCIO::GpuShaderDesc::TextureType channel = OCIO::GpuShaderDesc::TEXTURE_RGB_CHANNEL;
    OCIO::Interpolation interpolation = OCIO::INTERP_LINEAR;
    desc.getTexture(i, texture_name, sampler_name, width, height, channel, interpolation);
    const float* values = nullptr;
    desc.getTextureValues(i, values);
    const bool red = channel == OCIO::GpuShaderDesc::TEXTURE_RED_CHANNEL;
    const GLint internal_format = red ? GL_R32F : GL_RGB32F;
    const GLenum format = red ? GL_RED : GL_RGB;
    LutTexture lut{lut_target(text, sampler_name), sampler_name, gl::make_texture()};
    glBindTexture(lut.target, lut.texture.get());
    set_sampling(lut.target, filter_for(interpolation));
    if (lut.target == GL_TEXTURE_1D) {
      glTexImage1D(GL_TEXTURE_1D, 0, internal_format, static_cast<GLsizei>(width), 0, format,
                   GL_FLOAT, values);
    } else {
      glTexImage2D(GL_TEXTURE_2D, 0, internal_format, static_cast<GLsizei>(width),
                   static_cast<GLsizei>(height), 0, format, GL_FLOAT, values);
    }
    state.luts.push_back(std::move(lut));
  }
  for (unsigned i = 0; i < desc.getNum3DTextures(); ++i) {
    const char* texture_name = nullptr;
    const char* sampler_name = nullptr;
    unsigned edge = 0;
    OCIO::Interpolation interpolation = OCIO::INTERP_LINEAR;
    desc.get3DTexture(i, texture_name, sampler_name, edge, interpolation);
    const float* values = nullptr;
    desc.get3DTextureValues(i, values);
    LutTexture lut{GL_TEXTURE_3D, sampler_name, gl::make_texture()};
    glBindTexture(GL_TEXTURE_3D, lut.texture.get());
    set_sampling(GL_TEXTURE_3D, filter_for(interpolation));
    const auto size = static_cast<GLsizei>(edge);
    glTexImage3D(GL_TEXTURE_3D, 0, GL_RGB32F, size, size, size, 0, GL_RGB, GL_FLOAT, values);
    state.luts.push_back(std::move(lut));
  }
  glPixelStorei(GL_UNPACK_ALIGNMENT, previous_alignment);
  return Ok{};
}

Result<std::unique_ptr<GlState>> build_gl_state(const DisplayTransformData& data) {
  auto state = std::make_unique<GlState>();
  auto vertex = compile(GL_VERTEX_SHADER, kVertexShader, "vertex");
  if (!vertex) return vertex.error();
  auto fragment = compile(GL_FRAGMENT_SHADER, data.fragment_source, "OCIO fragment");
  if (!fragment) return fragment.error();
  state->program = gl::Program(glCreateProgram());
  const GLuint program = state->program.get();
  glAttachShader(program, vertex->get());
  glAttachShader(program, fragment->get());
  glLinkProgram(program);
  GLint linked = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &linked);
  if (linked != GL_TRUE) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
    glGetProgramInfoLog(program, length, nullptr, log.data());
    return make_error("display transform: the OCIO program does not link: " +
                      std::string(log.c_str()));
  }
  state->source_location = glGetUniformLocation(program, "aq_display_source");

  if (auto ok = upload_luts(data, *state); !ok) return ok.error();

  const auto& desc = *data.shader_desc;
  for (unsigned i = 0; i < desc.getNumUniforms(); ++i) {
    UniformBinding binding;
    const char* name = desc.getUniform(i, binding.data);
    binding.location = glGetUniformLocation(program, name);
    // A uniform the compiler optimised away has no location; nothing to set.
    if (binding.location >= 0) state->uniforms.push_back(binding);
  }
  state->vertex_array = gl::make_vertex_array();
  return state;
}

void set_uniforms(const GlState& state) {
  for (const auto& uniform : state.uniforms) {
    const auto& data = uniform.data;
    switch (data.m_type) {
      case OCIO::UNIFORM_DOUBLE:
        glUniform1f(uniform.location, static_cast<float>(data.m_getDouble()));
        break;
      case OCIO::UNIFORM_BOOL:
        glUniform1i(uniform.location, data.m_getBool() ? 1 : 0);
        break;
      case OCIO::UNIFORM_FLOAT3: {
        const auto v = data.m_getFloat3();
        glUniform3f(uniform.location, v[0], v[1], v[2]);
        break;
      }
      case OCIO::UNIFORM_VECTOR_FLOAT:
        glUniform1fv(uniform.location, static_cast<GLsizei>(data.m_vectorFloat.m_getSize()),
                     data.m_vectorFloat.m_getVector());
        break;
      case OCIO::UNIFORM_VECTOR_INT:
        glUniform1iv(uniform.location, static_cast<GLsizei>(data.m_vectorInt.m_getSize()),
                     data.m_vectorInt.m_getVector());
        break;
      case OCIO::UNIFORM_UNKNOWN:
        break;
    }
  }
}

// Saves the GL state this pass changes and restores it on scope exit, so the transform can be
// called between the evaluator's own passes.
class SavedGlState {
 public:
  SavedGlState() {
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer_);
    glGetIntegerv(GL_VIEWPORT, viewport_);
    glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertex_array_);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active_texture_);
    blend_ = glIsEnabled(GL_BLEND);
    depth_ = glIsEnabled(GL_DEPTH_TEST);
    scissor_ = glIsEnabled(GL_SCISSOR_TEST);
    cull_ = glIsEnabled(GL_CULL_FACE);
  }
  ~SavedGlState() {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(framebuffer_));
    glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
    glUseProgram(static_cast<GLuint>(program_));
    glBindVertexArray(static_cast<GLuint>(vertex_array_));
    glActiveTexture(static_cast<GLenum>(active_texture_));
    restore(GL_BLEND, blend_);
    restore(GL_DEPTH_TEST, depth_);
    restore(GL_SCISSOR_TEST, scissor_);
    restore(GL_CULL_FACE, cull_);
  }
  SavedGlState(const SavedGlState&) = delete;
  SavedGlState& operator=(const SavedGlState&) = delete;

 private:
  static void restore(GLenum capability, GLboolean enabled) {
    if (enabled) {
      glEnable(capability);
    } else {
      glDisable(capability);
    }
  }
  GLint framebuffer_ = 0, program_ = 0, vertex_array_ = 0, active_texture_ = GL_TEXTURE0;
  GLint viewport_[4] = {0, 0, 0, 0};
  GLboolean blend_ = GL_FALSE, depth_ = GL_FALSE, scissor_ = GL_FALSE, cull_ = GL_FALSE;
};

}  // namespace

Result<DisplayTransform> DisplayTransform::create(const ColorConfig& config,
                                                  const std::string& display,
                                                  const std::string& view) {
  auto data = std::make_shared<DisplayTransformData>();
  data->config = config.data();
  data->display = display.empty() ? config.default_display() : display;
  const auto displays = config.displays();
  if (!contains(displays, data->display)) {
    return make_error("display transform: unknown display \"" + data->display +
                      "\" in OCIO config " + config.path() +
                      "; available displays: " + join(displays));
  }
  const auto views = config.views(data->display);
  data->view = view.empty()
                   ? std::string(data->config->config->getDefaultView(data->display.c_str()))
                   : view;
  if (!contains(views, data->view)) {
    return make_error("display transform: unknown view \"" + data->view + "\" for display \"" +
                      data->display + "\" in OCIO config " + config.path() +
                      "; available views: " + join(views) + " (choose one with --view)");
  }
  try {
    auto transform = OCIO::DisplayViewTransform::Create();
    transform->setSrc(config.working_space().c_str());
    transform->setDisplay(data->display.c_str());
    transform->setView(data->view.c_str());
    auto processor = data->config->config->getProcessor(transform);
    data->cpu = processor->getDefaultCPUProcessor();
    data->shader_desc = OCIO::GpuShaderDesc::CreateShaderDesc();
    data->shader_desc->setLanguage(OCIO::GPU_LANGUAGE_GLSL_4_0);
    data->shader_desc->setFunctionName(kFunctionName);
    data->shader_desc->setResourcePrefix(kResourcePrefix);
    processor->getDefaultGPUProcessor()->extractGpuShaderInfo(data->shader_desc);
  } catch (const OCIO::Exception& e) {
    return make_error("display transform: OCIO cannot build display \"" + data->display +
                      "\", view \"" + data->view + "\" from config " + config.path() + ": " +
                      e.what());
  }
  data->fragment_source =
      std::string("#version 450 core\n") + data->shader_desc->getShaderText() + kFragmentMain;
  return DisplayTransform(std::move(data));
}

const std::string& DisplayTransform::display() const {
  return data_->display;
}
const std::string& DisplayTransform::view() const {
  return data_->view;
}
const std::string& DisplayTransform::shader_source() const {
  return data_->fragment_source;
}

Status DisplayTransform::apply_cpu(ImageF& image) const {
  if (image.empty()) return Ok{};
  if (image.channels != 3 && image.channels != 4) {
    return make_error("display transform: the image has " + std::to_string(image.channels) +
                      " channels; only RGB and RGBA images can be transformed");
  }
  if (image.channels == 4) {
    const size_t count = static_cast<size_t>(image.width) * image.height;
    for (size_t i = 0; i < count; ++i) {
      float* px = image.pixels.data() + i * 4;
      if (px[3] > 0.0f) {
        px[0] /= px[3];
        px[1] /= px[3];
        px[2] /= px[3];
      }
    }
  }
  try {
    OCIO::PackedImageDesc desc(image.pixels.data(), image.width, image.height, image.channels);
    data_->cpu->apply(desc);
  } catch (const OCIO::Exception& e) {
    return make_error(std::string("display transform (CPU): ") + e.what());
  }
  return Ok{};
}

Result<gl::Texture> DisplayTransform::apply(GLuint source_texture, int width, int height) const {
  if (width <= 0 || height <= 0) {
    return make_error("display transform: invalid size " + std::to_string(width) + "x" +
                      std::to_string(height));
  }
  if (!data_->gl) {
    auto state = build_gl_state(*data_);
    if (!state) return state.error();
    data_->gl = std::move(*state);
  }
  const GlState& state = *data_->gl;
  SavedGlState saved;
  while (glGetError() != GL_NO_ERROR) {
    // Errors of earlier passes are not ours to report.
  }

  gl::Texture target = gl::make_texture();
  glBindTexture(GL_TEXTURE_2D, target.get());
  glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, width, height);
  set_sampling(GL_TEXTURE_2D, GL_LINEAR);
  gl::Framebuffer framebuffer = gl::make_framebuffer();
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer.get());
  glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target.get(), 0);
  const GLenum status = glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    return make_error(
        "display transform: the RGBA32F target framebuffer is incomplete (GL "
        "status " +
        std::to_string(status) + ")");
  }
  glViewport(0, 0, width, height);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_CULL_FACE);
  glUseProgram(state.program.get());

  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, source_texture);
  glUniform1i(state.source_location, 0);
  for (size_t i = 0; i < state.luts.size(); ++i) {
    const GLint unit = static_cast<GLint>(i + 1);
    glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
    glBindTexture(state.luts[i].target, state.luts[i].texture.get());
    glUniform1i(glGetUniformLocation(state.program.get(), state.luts[i].sampler.c_str()), unit);
  }
  set_uniforms(state);

  glBindVertexArray(state.vertex_array.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  if (const GLenum error = glGetError(); error != GL_NO_ERROR) {
    return make_error("display transform: GL error " + std::to_string(error) +
                      " while drawing (is the source a GL_TEXTURE_2D of " + std::to_string(width) +
                      "x" + std::to_string(height) + "?)");
  }
  return target;
}

void DisplayTransform::release_gl() const {
  data_->gl.reset();
}

}  // namespace aq
