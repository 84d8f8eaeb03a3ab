// ShaderCache: preprocessing (#version, #include, #line), compilation, error mapping, caching.
#include "shader_cache.h"

#include <fstream>
#include <regex>
#include <sstream>
#include <string_view>
#include <vector>

#include "shader_library_sources.h"

namespace aq {

namespace {

// Instance i of the triangle goes to viewport i, whose scissor box is rect i of a draw region
// (HostServices::draw_fullscreen): the same triangle, so the same pixels and interpolated values
// as one draw per rect, in a sixteenth of the draw calls.
constexpr const char* kFullscreenVertex = R"(#extension GL_ARB_shader_viewport_layer_array : enable
out vec2 v_uv;
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  v_uv = p;
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
#ifdef GL_ARB_shader_viewport_layer_array
  gl_ViewportIndex = gl_InstanceID;
#endif
}
)";

const aq_shader_source kFullscreenSource = {"fullscreen.vert", kFullscreenVertex, nullptr};

struct Expanded {
  std::string text;
  std::vector<std::string> files;  // GLSL source-string number -> file name
};

std::string read_text(const aq_shader_source& source, bool hot_reload) {
  if (hot_reload && source.path != nullptr) {
    std::ifstream file(source.path);
    if (file) {
      std::stringstream buffer;
      buffer << file.rdbuf();
      return buffer.str();
    }
  }
  return source.text != nullptr ? source.text : "";
}

const aq_shader_source* find_library(const std::string& name) {
  for (const aq_shader_source* const* it = shaders::all; *it != nullptr; ++it) {
    if (name == std::string("aquarelle/") + (*it)->name) return *it;
  }
  return nullptr;
}

Status expand(const std::string& name, const std::string& text, Expanded& out, bool hot_reload,
              int depth) {
  if (depth > 8) return make_error(name + ": #include nested too deeply (a cycle?)");
  int file_number = static_cast<int>(out.files.size());
  out.files.push_back(name);
  std::istringstream lines(text);
  std::string line;
  int line_number = 0;
  static const std::regex include_line(R"(^\s*#\s*include\s*[<"]([^">]+)[">]\s*$)");
  out.text += "#line 1 " + std::to_string(file_number) + "\n";
  while (std::getline(lines, line)) {
    ++line_number;
    std::smatch match;
    if (std::regex_match(line, match, include_line)) {
      const aq_shader_source* library = find_library(match[1]);
      if (library == nullptr) {
        std::string known;
        for (const aq_shader_source* const* it = shaders::all; *it != nullptr; ++it) {
          known += std::string(known.empty() ? "" : ", ") + "aquarelle/" + (*it)->name;
        }
        return make_error(name + ":" + std::to_string(line_number) + ": unknown include '" +
                          match[1].str() + "' (available: " + known + ")");
      }
      if (auto status = expand(library->name, read_text(*library, hot_reload), out, hot_reload,
                               depth + 1);
          !status.ok()) {
        return status;
      }
      out.text += "#line " + std::to_string(line_number + 1) + " " +
                  std::to_string(file_number) + "\n";
      continue;
    }
    out.text += line + "\n";
  }
  return Ok{};
}

// Mesa: "0:12(5): error: ..."; others: "ERROR: 0:12: ...". Rewrites source numbers to names.
std::string map_log(const std::string& log, const std::vector<std::string>& files) {
  static const std::regex location(R"((\d+):(\d+)\((\d+)\))");
  static const std::regex location2(R"(ERROR: (\d+):(\d+):)");
  std::istringstream lines(log);
  std::string line, out;
  while (std::getline(lines, line)) {
    if (line.empty()) continue;
    std::smatch m;
    auto name_of = [&](const std::string& n) {
      size_t i = std::stoul(n);
      return i < files.size() ? files[i] : "source " + n;
    };
    if (std::regex_search(line, m, location)) {
      line = name_of(m[1]) + ":" + m[2].str() + ":" + m[3].str() + m.suffix().str();
    } else if (std::regex_search(line, m, location2)) {
      line = name_of(m[1]) + ":" + m[2].str() + ":" + m.suffix().str();
    }
    out += (out.empty() ? "" : "\n") + line;
  }
  return out;
}

Result<gl::Shader> compile(GLenum stage, const Expanded& source) {
  gl::Shader shader(glCreateShader(stage));
  std::string text = "#version 450 core\n" + source.text;
  const char* pointer = text.c_str();
  glShaderSource(shader.get(), 1, &pointer, nullptr);
  glCompileShader(shader.get());
  GLint ok = 0;
  glGetShaderiv(shader.get(), GL_COMPILE_STATUS, &ok);
  if (ok == GL_TRUE) return shader;
  GLint length = 0;
  glGetShaderiv(shader.get(), GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
  glGetShaderInfoLog(shader.get(), length, nullptr, log.data());
  return make_error_lines("shader does not compile:\n" + map_log(log.c_str(), source.files));
}

}  // namespace

Result<GLuint> ShaderCache::program(const aq_shader_source* vertex,
                                    const aq_shader_source* fragment) {
  if (fragment == nullptr) return make_error("no fragment shader given");
  const aq_shader_source& vs = vertex != nullptr ? *vertex : kFullscreenSource;
  std::string given;
  if (!hot_reload_) {
    // Both texts with their lengths: no pair of sources can produce another pair's key.
    const std::string_view vs_given = vs.text != nullptr ? vs.text : "";
    const std::string_view fs_given = fragment->text != nullptr ? fragment->text : "";
    given.reserve(vs_given.size() + fs_given.size() + 24);
    given.append(std::to_string(vs_given.size())).append(1, ':').append(vs_given);
    given.append(fs_given);
    if (auto it = by_given_source_.find(given); it != by_given_source_.end()) return it->second;
  }
  Expanded vs_text, fs_text;
  if (auto s = expand(vs.name ? vs.name : "vertex", read_text(vs, hot_reload_), vs_text,
                      hot_reload_, 0);
      !s.ok()) {
    return s.error();
  }
  if (auto s = expand(fragment->name ? fragment->name : "fragment",
                      read_text(*fragment, hot_reload_), fs_text, hot_reload_, 0);
      !s.ok()) {
    return s.error();
  }
  std::string key = vs_text.text + "\n//----\n" + fs_text.text;
  if (auto it = programs_.find(key); it != programs_.end()) {
    if (!hot_reload_) by_given_source_.emplace(std::move(given), it->second.get());
    return it->second.get();
  }

  auto vs_shader = compile(GL_VERTEX_SHADER, vs_text);
  if (!vs_shader.ok()) return vs_shader.error();
  auto fs_shader = compile(GL_FRAGMENT_SHADER, fs_text);
  if (!fs_shader.ok()) return fs_shader.error();
  gl::Program program(glCreateProgram());
  glAttachShader(program.get(), vs_shader->get());
  glAttachShader(program.get(), fs_shader->get());
  glLinkProgram(program.get());
  GLint ok = 0;
  glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
  glDetachShader(program.get(), vs_shader->get());
  glDetachShader(program.get(), fs_shader->get());
  if (ok != GL_TRUE) {
    GLint length = 0;
    glGetProgramiv(program.get(), GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
    glGetProgramInfoLog(program.get(), length, nullptr, log.data());
    return make_error("shader program does not link (" + std::string(vs.name ? vs.name : "") +
                      " + " + (fragment->name ? fragment->name : "") + "):\n" + log.c_str());
  }
  GLuint id = program.get();
  if (vertex == nullptr) fullscreen_.insert(id);
  programs_.emplace(std::move(key), std::move(program));
  if (!hot_reload_) by_given_source_.emplace(std::move(given), id);
  return id;
}

}  // namespace aq
