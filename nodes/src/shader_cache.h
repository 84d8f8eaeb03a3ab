// Compiles and links plugin shaders, once per distinct source. Resolves
// `#include "aquarelle/<file>.glsl"` from the embedded shared library (nodes/shaders/) and maps
// compiler messages back to the file and line they came from.
#pragma once

#include <aquarelle/core/gl_objects.h>
#include <aquarelle/core/result.h>
#include <aquarelle/plugin.h>

#include <map>
#include <string>
#include <unordered_map>
#include <unordered_set>

namespace aq {

class ShaderCache {
 public:
  // vertex may be null: the full-screen triangle, which passes `v_uv` to the fragment shader.
  Result<GLuint> program(const aq_shader_source* vertex, const aq_shader_source* fragment);
  void set_hot_reload(bool enabled) { hot_reload_ = enabled; }
  size_t size() const { return programs_.size(); }
  // Whether `program` runs the full-screen triangle (its instance i draws into viewport i).
  bool fullscreen(GLuint program) const { return fullscreen_.count(program) != 0; }

 private:
  std::map<std::string, gl::Program> programs_;
  // The program of each pair of sources as given (before #include expansion), so that a node
  // asking for its program every frame costs a hash, not the expansion (a regex match per line
  // of every included file: 16 % of the flagship's main thread per frame). Not used
  // with hot reload, where an included file may change on disk between two calls.
  std::unordered_map<std::string, GLuint> by_given_source_;
  std::unordered_set<GLuint> fullscreen_;
  bool hot_reload_ = false;
};

}  // namespace aq
