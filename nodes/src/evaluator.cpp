// Evaluator: pull-based evaluation with per-node cache keys, texture release after the last
// reader, and GPU timing. The host services a plugin sees (aq_host) are implemented here too,
// because each of them acts on the node being processed.
#include <aquarelle/core/evaluator.h>

#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/quality.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <functional>
#include <set>

#include "builtin_nodes.h"
#include "hash.h"
#include "host_image_service.h"
#include "pointwise_fusion.h"
#include "shader_cache.h"

namespace aq {

namespace {

uint32_t working_format(const std::string& precision) {
  return precision == "float" ? AQ_FORMAT_RGBA32F : AQ_FORMAT_RGBA16F;
}

}  // namespace

struct NodeState {
  const NodeType* type = nullptr;
  void* instance = nullptr;
  uint64_t key = 0;
  bool valid = false;  // outputs hold the result for `key`
  std::vector<TextureRef> images;
  std::vector<const aq_scene*> scenes;
  gl::Query timer_start;  // GL_TIMESTAMP pairs: llvmpipe's GL_TIME_ELAPSED reads garbage when
  gl::Query timer_end;    // a query spans shader compilation, timestamps do not
  BuiltinState builtin;

  // GL_TIMESTAMP pair around this node's work.
  void mark_start() {
    if (!timer_start) {
      timer_start = gl::make_query();
      timer_end = gl::make_query();
    }
    glQueryCounter(timer_start.get(), GL_TIMESTAMP);
  }
  void mark_end() { glQueryCounter(timer_end.get(), GL_TIMESTAMP); }
  double marked_gpu_ms() const {
    GLuint64 begin_ns = 0, end_ns = 0;
    glGetQueryObjectui64v(timer_start.get(), GL_QUERY_RESULT, &begin_ns);
    glGetQueryObjectui64v(timer_end.get(), GL_QUERY_RESULT, &end_ns);
    return end_ns > begin_ns ? static_cast<double>(end_ns - begin_ns) * 1e-6 : 0.0;
  }
};

struct CallState {
  Evaluator::Impl* impl = nullptr;
  NodeState* state = nullptr;
  std::string node_id;
  std::string error;
  std::vector<TextureRef> scratch;
  const std::vector<TextureRef>* input_refs = nullptr;
};

// The deferred stages of a fused chain of pointwise nodes, kept until the node that ends the
// chain runs them in one pass (pointwise_fusion.h). Each stage keeps the parameters and context
// its node's process() would have seen.
struct FusedChain {
  struct Stage {
    const NodeType* type = nullptr;
    void* instance = nullptr;
    std::vector<aq_param_value> params;
    std::vector<std::string> strings;  // params[i].s points into these
    std::vector<aq_input_value> inputs;
    CallState call;
    aq_process_ctx ctx{};
  };
  TextureRef input;  // the image the first stage reads
  std::vector<std::unique_ptr<Stage>> stages;
};

// The context process() (or a fused stage's set_uniforms) sees for one node.
void fill_process_ctx(aq_process_ctx& ctx, const aq_host* host, uint32_t gl_generation,
                      CallState& call, std::vector<aq_input_value>& inputs,
                      std::vector<aq_param_value>& params, const Settings& settings,
                      uint32_t format, double time, int frame, const PixelSize& size) {
  ctx.struct_size = sizeof(aq_process_ctx);
  ctx.host = host;
  ctx.host_data = &call;
  ctx.node_id = call.node_id.c_str();
  ctx.inputs = inputs.data();
  ctx.input_count = static_cast<uint32_t>(inputs.size());
  ctx.params = params.data();
  ctx.param_count = static_cast<uint32_t>(params.size());
  ctx.width = size.width;
  ctx.height = size.height;
  ctx.precision = settings.precision == "float" ? AQ_PRECISION_FLOAT : AQ_PRECISION_HALF;
  ctx.working_format = format;
  ctx.time = time;
  ctx.frame = frame;
  ctx.fps = settings.fps;
  ctx.gl_generation = gl_generation;
  ctx.quality = quality_index(settings.quality);
  ctx.render_scale = render_scale(settings.quality);
  ctx.input_lists = nullptr;
}

// Pointwise nodes whose function runs inside their reader's pass instead of a pass of their
// own: they give a fusable function, are not the output, and their only reader is another
// such node reading them on its image input.
std::set<std::string> deferred_nodes(const Graph& graph, const Registry& registry,
                                     const std::vector<std::string>& order,
                                     std::map<std::string, int>& readers,
                                     const std::string& target) {
  std::set<std::string> deferred;
  auto fusable = [&](const std::string& id) {
    const NodeType* type = registry.find(graph.nodes.at(id).type);
    return type != nullptr && type->fusable != nullptr;
  };
  for (const auto& reader_id : order) {
    if (!fusable(reader_id)) continue;
    const NodeType* reader_type = registry.find(graph.nodes.at(reader_id).type);
    const Node& reader = graph.nodes.at(reader_id);
    auto link = reader.inputs.find(reader_type->inputs[0].name);
    if (link == reader.inputs.end()) continue;
    const std::string& source = link->second.node;
    if (source != target && readers[source] == 1 && fusable(source)) deferred.insert(source);
  }
  return deferred;
}

struct Evaluator::Impl {
  GlContext& context;
  TexturePool& pool;
  ShaderCache shaders;
  PointwiseFuser fuser;
  std::map<std::string, NodeState> states;
  gl::VertexArray empty_vao;
  gl::Framebuffer framebuffer;
  GLuint attached_colors = 0;
  aq_host host{};

  Impl(GlContext& c, TexturePool& p) : context(c), pool(p) {
    host.abi_version = AQ_ABI_VERSION;
    host.struct_size = sizeof(aq_host);
    host.get_proc_address = &Impl::get_proc_address;
    host.fail = &Impl::fail;
    host.log = &Impl::log;
    host.program = &Impl::program;
    host.output_image = &Impl::output_image;
    host.pass_through = &Impl::pass_through;
    host.output_scene = &Impl::output_scene;
    host.scratch_image = &Impl::scratch_image;
    host.bind_targets = &Impl::bind_targets;
    host.draw_fullscreen = &Impl::draw_fullscreen;
    host.read_image = &host_read_image;
  }

  ~Impl() { destroy_all(); }

  void destroy_state(NodeState& state) {
    state.images.clear();
    state.scenes.clear();
    if (state.instance != nullptr && state.type != nullptr && state.type->desc != nullptr) {
      state.type->desc->destroy(state.instance);
    }
    state.instance = nullptr;
    state.valid = false;
  }
  void destroy_all() {
    if (!states.empty()) context.activate();
    for (auto& [id, state] : states) destroy_state(state);
    states.clear();
  }

  static Impl* current_impl;
  static void* get_proc_address(const char* name) {
    return current_impl != nullptr ? current_impl->context.get_proc_address(name) : nullptr;
  }
  static void fail(void* data, const char* message) {
    auto* call = static_cast<CallState*>(data);
    if (!call->error.empty()) call->error += "\n";
    call->error += message != nullptr ? message : "(no message)";
  }
  static void log(void* data, int level, const char* message) {
    auto* call = static_cast<CallState*>(data);
    std::fprintf(stderr, "%s: node '%s': %s\n", level > 0 ? "warning" : "info",
                 call->node_id.c_str(), message);
  }
  static uint32_t program(void* data, const aq_shader_source* vertex,
                          const aq_shader_source* fragment) {
    auto* call = static_cast<CallState*>(data);
    auto result = call->impl->shaders.program(vertex, fragment);
    if (!result.ok()) {
      fail(data, result.message().c_str());
      return 0;
    }
    return *result;
  }
  static bool valid_size(CallState* call, int32_t width, int32_t height) {
    GLint limit = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &limit);
    if (width < 1 || height < 1 || width > limit || height > limit) {
      fail(call, ("cannot make a " + std::to_string(width) + "x" + std::to_string(height) +
                  " texture: sizes run from 1x1 to " + std::to_string(limit) + "x" +
                  std::to_string(limit) + " on this GL implementation")
                     .c_str());
      return false;
    }
    return true;
  }
  static int output_image(void* data, uint32_t index, int32_t width, int32_t height,
                          uint32_t format, aq_image* out) {
    auto* call = static_cast<CallState*>(data);
    NodeState& state = *call->state;
    if (index >= state.images.size() || state.type->outputs[index].type != AQ_PORT_IMAGE) {
      fail(data, ("output_image: no image output with index " + std::to_string(index)).c_str());
      return AQ_ERROR;
    }
    if (!valid_size(call, width, height)) return AQ_ERROR;
    state.images[index] = call->impl->pool.acquire(width, height, format);
    *out = state.images[index]->image;
    return AQ_OK;
  }
  static int pass_through(void* data, uint32_t index, uint32_t input_index) {
    auto* call = static_cast<CallState*>(data);
    NodeState& state = *call->state;
    if (index >= state.images.size() || call->input_refs == nullptr ||
        input_index >= call->input_refs->size() || !(*call->input_refs)[input_index]) {
      fail(data, "pass_through: no such image output or connected image input");
      return AQ_ERROR;
    }
    state.images[index] = (*call->input_refs)[input_index];
    return AQ_OK;
  }
  static int output_scene(void* data, uint32_t index, const aq_scene* scene) {
    auto* call = static_cast<CallState*>(data);
    NodeState& state = *call->state;
    if (index >= state.scenes.size() || state.type->outputs[index].type != AQ_PORT_SCENE) {
      fail(data, ("output_scene: no scene output with index " + std::to_string(index)).c_str());
      return AQ_ERROR;
    }
    state.scenes[index] = scene;
    return AQ_OK;
  }
  static int scratch_image(void* data, int32_t width, int32_t height, uint32_t format,
                           aq_image* out) {
    auto* call = static_cast<CallState*>(data);
    if (!valid_size(call, width, height)) return AQ_ERROR;
    call->scratch.push_back(call->impl->pool.acquire(width, height, format));
    *out = call->scratch.back()->image;
    return AQ_OK;
  }
  static int bind_targets(void* data, const aq_image* colors, uint32_t count,
                          const aq_image* depth) {
    auto* call = static_cast<CallState*>(data);
    Impl& impl = *call->impl;
    GLuint fbo = impl.framebuffer.get();
    GLint max_attachments = 8;
    glGetIntegerv(GL_MAX_COLOR_ATTACHMENTS, &max_attachments);
    if (count > static_cast<uint32_t>(max_attachments)) {
      fail(data, "bind_targets: too many colour targets");
      return AQ_ERROR;
    }
    std::vector<GLenum> buffers;
    for (uint32_t i = 0; i < count; ++i) {
      glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0 + i, colors[i].texture, 0);
      buffers.push_back(GL_COLOR_ATTACHMENT0 + i);
    }
    for (GLuint i = count; i < impl.attached_colors; ++i) {
      glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0 + i, 0, 0);
    }
    impl.attached_colors = count;
    glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depth != nullptr ? depth->texture : 0, 0);
    if (count > 0) {
      glNamedFramebufferDrawBuffers(fbo, static_cast<GLsizei>(count), buffers.data());
    } else {
      glNamedFramebufferDrawBuffer(fbo, GL_NONE);
    }
    GLenum status = glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
      char text[96];
      std::snprintf(text, sizeof(text), "bind_targets: framebuffer incomplete (0x%04X)", status);
      fail(data, text);
      return AQ_ERROR;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    const aq_image& size_of = count > 0 ? colors[0] : *depth;
    glViewport(0, 0, size_of.width, size_of.height);
    return AQ_OK;
  }
  static void draw_fullscreen(void* data) {
    auto* call = static_cast<CallState*>(data);
    glBindVertexArray(call->impl->empty_vao.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
  }

  // Leaves GL as the next node expects to find it, whatever this node left bound.
  void reset_gl_state() {
    glUseProgram(0);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    for (GLuint unit = 0; unit < 8; ++unit) {
      glActiveTexture(GL_TEXTURE0 + unit);
      glBindTexture(GL_TEXTURE_2D, 0);
    }
    glActiveTexture(GL_TEXTURE0);
  }
};

Evaluator::Impl* Evaluator::Impl::current_impl = nullptr;

Evaluator::Evaluator(GlContext& context, const Registry& registry)
    : context_(context), registry_(registry), pool_(std::make_unique<TexturePool>()) {
  context_.activate();
  impl_ = std::make_unique<Impl>(context_, *pool_);
  impl_->empty_vao = gl::make_vertex_array();
  glCreateFramebuffers(1, reinterpret_cast<GLuint*>(&impl_->attached_colors));
  impl_->framebuffer = gl::Framebuffer(impl_->attached_colors);
  impl_->attached_colors = 0;
}

Evaluator::~Evaluator() {
  context_.activate();
  impl_.reset();  // node instances and their outputs go before the pool
  pool_.reset();
}

void Evaluator::clear() {
  context_.activate();
  impl_->destroy_all();
}

void Evaluator::set_shader_hot_reload(bool enabled) {
  impl_->shaders.set_hot_reload(enabled);
}

Result<ImageF> read_texture(GLuint texture, int width, int height, uint32_t format) {
  bool single = format == AQ_FORMAT_R32F || format == AQ_FORMAT_DEPTH32F;
  ImageF out(width, height, single ? 1 : 4);
  while (glGetError() != GL_NO_ERROR) {
  }  // only this read's error counts below
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  if (format == AQ_FORMAT_R32UI) {
    std::vector<uint32_t> ids(static_cast<size_t>(width) * height);
    glGetTextureImage(texture, 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
                      static_cast<GLsizei>(ids.size() * 4), ids.data());
    out = ImageF(width, height, 1);
    for (size_t i = 0; i < ids.size(); ++i) out.pixels[i] = static_cast<float>(ids[i]);
    return out;
  }
  GLenum gl_format =
      format == AQ_FORMAT_DEPTH32F ? GL_DEPTH_COMPONENT : (single ? GL_RED : GL_RGBA);
  glGetTextureImage(texture, 0, gl_format, GL_FLOAT,
                    static_cast<GLsizei>(out.pixels.size() * sizeof(float)), out.pixels.data());
  if (GLenum error = glGetError(); error != GL_NO_ERROR) {
    char text[96];
    std::snprintf(text, sizeof(text), "reading the texture back failed (GL error 0x%04X)", error);
    return make_error(text);
  }
  return out;
}

Result<ImageF> Evaluator::read_back(const TextureRef& texture) {
  if (!texture) return make_error("nothing to read back");
  context_.activate();
  const aq_image& image = texture->image;
  return read_texture(image.texture, image.width, image.height, image.format);
}

Result<TextureRef> Evaluator::evaluate(const Graph& graph, const EvalOptions& options,
                                       const std::optional<PortRef>& requested) {
  timings_.clear();
  if (!context_.activate()) return make_error("the OpenGL context cannot be made current");
  Impl::current_impl = impl_.get();
  std::optional<PortRef> target = requested ? requested : graph.output;
  if (!target)
    return make_error(
        "the graph has no `output`: name the port to render, e.g. "
        "\"output\": \"tint.image\"");
  if (graph.nodes.find(target->node) == graph.nodes.end()) {
    return make_error("output '" + target->str() + "' names node '" + target->node +
                      "', which is not in the graph");
  }

  // Drop state of nodes that left the graph or changed type.
  for (auto it = impl_->states.begin(); it != impl_->states.end();) {
    auto node = graph.nodes.find(it->first);
    if (node == graph.nodes.end() || it->second.type == nullptr ||
        node->second.type != it->second.type->name) {
      impl_->destroy_state(it->second);
      it = impl_->states.erase(it);
    } else {
      ++it;
    }
  }

  // Cull to what the output depends on and sort (depth-first, inputs before readers).
  std::vector<std::string> order;
  std::map<std::string, int> mark;  // 1 visiting, 2 done
  std::function<Status(const std::string&, std::vector<std::string>&)> visit =
      [&](const std::string& id, std::vector<std::string>& path) -> Status {
    if (mark[id] == 2) return Ok{};
    path.push_back(id);
    if (mark[id] == 1) {
      std::string cycle;
      auto start = std::find(path.begin(), path.end(), id);
      for (auto it = start; it != path.end(); ++it) cycle += (cycle.empty() ? "" : " -> ") + *it;
      return make_error("the graph has a cycle: " + cycle);
    }
    mark[id] = 1;
    auto node = graph.nodes.find(id);
    if (node == graph.nodes.end()) return make_error("node '" + id + "' is not in the graph");
    for (const auto& [port, source] : node->second.inputs) {
      if (graph.nodes.find(source.node) == graph.nodes.end()) {
        return make_error("node '" + id + "', input '" + port + "': source node '" + source.node +
                          "' is not in the graph");
      }
      if (auto s = visit(source.node, path); !s.ok()) return s;
    }
    mark[id] = 2;
    path.pop_back();
    order.push_back(id);
    return Ok{};
  };
  std::vector<std::string> path;
  if (auto s = visit(target->node, path); !s.ok()) return s.error();

  // Readers per producer, so outputs can go back to the pool after their last use.
  std::map<std::string, int> readers;
  for (const auto& id : order) {
    for (const auto& [port, source] : graph.nodes.at(id).inputs) ++readers[source.node];
  }
  readers[target->node] += 1;

  std::map<std::string, bool> varies;

  const std::set<std::string> deferred =
      options.fuse_pointwise ? deferred_nodes(graph, registry_, order, readers, target->node)
                             : std::set<std::string>{};
  // The stages of each fused chain so far, by the id of its last deferred node.
  std::map<std::string, std::shared_ptr<FusedChain>> chains;
  const Settings& settings = graph.settings;
  const uint32_t format = working_format(settings.precision);
  const double time = (options.frame - settings.first_frame) / std::max(settings.fps, 1e-6);
  const PixelSize working = working_size(settings);
  std::filesystem::path graph_dir = graph.source_path.empty()
                                        ? std::filesystem::path()
                                        : std::filesystem::path(graph.source_path).parent_path();

  for (const auto& id : order) {
    const Node& node = graph.nodes.at(id);
    const NodeType* type = registry_.find(node.type);
    if (type == nullptr) {
      return make_error("node '" + id + "': unknown node type '" + node.type +
                        "' (run `aquarelle nodes` to list the installed types)");
    }
    NodeState& state = impl_->states[id];
    state.type = type;
    if (state.images.size() != type->outputs.size()) {
      state.images.assign(type->outputs.size(), nullptr);
      state.scenes.assign(type->outputs.size(), nullptr);
      state.valid = false;
    }

    // Parameters, as the ABI passes them.
    std::vector<aq_param_value> params(type->params.size());
    std::vector<std::string> strings(type->params.size());
    uint64_t key = kHashSeed;
    key = hash_string(key, type->name);
    for (size_t p = 0; p < type->params.size(); ++p) {
      const ParamInfo& info = type->params[p];
      nlohmann::json value = param_value_or_default(node, info);
      // replace, not throw, on invalid UTF-8 from --set or the editor
      key = hash_string(key, value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
      aq_param_value& out = params[p];
      out = aq_param_value{{0, 0, 0}, 0, nullptr};
      switch (info.type) {
        case AQ_PARAM_FLOAT:
          out.f[0] = value.is_number() ? value.get<double>() : info.default_value[0];
          break;
        case AQ_PARAM_INT:
          out.i = value.is_number() ? value.get<int64_t>()
                                    : static_cast<int64_t>(info.default_value[0]);
          out.f[0] = static_cast<double>(out.i);
          break;
        case AQ_PARAM_BOOL:
          out.i = value.is_boolean() ? (value.get<bool>() ? 1 : 0) : (info.default_value[0] != 0);
          break;
        case AQ_PARAM_ENUM: {
          out.i = static_cast<int64_t>(info.default_value[0]);
          if (value.is_string()) {
            for (size_t e = 0; e < info.enum_values.size(); ++e) {
              if (info.enum_values[e] == value.get<std::string>()) out.i = static_cast<int64_t>(e);
            }
          } else if (value.is_number_integer()) {
            out.i = value.get<int64_t>();
          }
          break;
        }
        case AQ_PARAM_COLOR:
        case AQ_PARAM_VEC3:
          for (int c = 0; c < 3; ++c) {
            out.f[c] = value.is_array() && value.size() == 3 && value[c].is_number()
                           ? value[c].get<double>()
                           : info.default_value[c];
          }
          break;
        case AQ_PARAM_STRING:
        case AQ_PARAM_PATH: {
          strings[p] = value.is_string() ? value.get<std::string>() : info.default_string;
          if (info.type == AQ_PARAM_PATH && !strings[p].empty() &&
              std::filesystem::path(strings[p]).is_relative() && !graph_dir.empty()) {
            strings[p] = (graph_dir / strings[p]).lexically_normal().string();
          }
          out.s = strings[p].c_str();
          break;
        }
      }
    }

    // Inputs, and the key they contribute.
    std::vector<aq_input_value> inputs(type->inputs.size());
    std::vector<TextureRef> input_refs(type->inputs.size());
    std::vector<std::vector<aq_input_value>> links(type->inputs.size());  // AQ_PORT_MULTI ports
    std::vector<aq_input_list> input_lists;
    for (size_t i = 0; i < type->inputs.size(); ++i) {
      const PortInfo& port = type->inputs[i];
      aq_input_value& in = inputs[i];
      in = aq_input_value{static_cast<uint32_t>(port.type), 0, {0, 0, 0, 0}, nullptr};
      if (port.multi) {  // every link, in graph order (multi ports are scene ports)
        auto [first, last] = node.inputs.equal_range(port.name);
        for (auto link = first; link != last; ++link) {
          NodeState& source = impl_->states[link->second.node];
          const int index =
              source.type != nullptr ? source.type->output_index(link->second.port) : -1;
          if (index < 0 || source.type->outputs[index].type != AQ_PORT_SCENE) {
            return make_error("node '" + id + "', input '" + port.name + "': '" +
                              link->second.str() + "' is not a scene output");
          }
          key = hash_value(key, source.key);
          key = hash_string(key, link->second.port);
          links[i].push_back(aq_input_value{AQ_PORT_SCENE, 1, {0, 0, 0, 0}, source.scenes[index]});
        }
        key = hash_value(key, links[i].size());
        if (!links[i].empty()) in = links[i][0];
        continue;
      }
      auto link = node.inputs.find(port.name);
      if (link == node.inputs.end()) {
        if (!port.optional) {
          return make_error("node '" + id + "' (" + type->name + "): required input '" + port.name +
                            "' is not connected");
        }
        key = hash_string(key, "-");
        continue;
      }
      NodeState& source = impl_->states[link->second.node];
      int index = source.type != nullptr ? source.type->output_index(link->second.port) : -1;
      if (index < 0) {
        return make_error("node '" + id + "', input '" + port.name + "': '" + link->second.str() +
                          "' is not an output port");
      }
      if (source.type->outputs[index].type != port.type) {
        return make_error("node '" + id + "', input '" + port.name + "': expects " +
                          port_type_name(port.type) + " but '" + link->second.str() + "' gives " +
                          port_type_name(source.type->outputs[index].type));
      }
      key = hash_value(key, source.key);
      key = hash_string(key, link->second.port);
      in.connected = 1;
      if (port.type == AQ_PORT_IMAGE) {
        input_refs[i] = source.images[index];
        if (input_refs[i]) in.image = input_refs[i]->image;
      } else {
        in.scene = source.scenes[index];
      }
    }
    for (size_t i = 0; i < inputs.size() && type->has_multi_input(); ++i) {
      input_lists.push_back(
          links[i].empty() && inputs[i].connected != 0
              ? aq_input_list{&inputs[i], 1}
              : aq_input_list{links[i].data(), static_cast<uint32_t>(links[i].size())});
    }
    key = hash_value(key, settings.width);
    key = hash_value(key, settings.height);
    key = hash_value(key, format);
    key = hash_value(key, quality_index(settings.quality));
    if (type->time_dependent()) key = hash_value(key, options.frame);
    key = builtin_key(*type, params, options, key);

    // Fusion: a deferred node only records its stage; the node reading it runs the chain.
    std::shared_ptr<FusedChain> chain;
    if (type->fusable != nullptr && node.inputs.count(type->inputs[0].name) != 0) {
      const std::string& source = node.inputs.at(type->inputs[0].name).node;
      if (auto found = chains.find(source); found != chains.end()) {
        chain = found->second;
        chains.erase(found);
      }
    }
    const bool is_deferred = deferred.count(id) != 0;
    // The output's pointwise tail runs in the pass that resamples a proxy render's output.
    // Nodes without inputs (image_input, generators) have no input_refs[0].
    const TextureRef chain_input =
        chain ? chain->input : (input_refs.empty() ? TextureRef() : input_refs[0]);
    const bool tail_into_resample =
        !is_deferred && options.fuse_pointwise && type->fusable != nullptr && id == target->node &&
        (working.width != settings.width || working.height != settings.height) && chain_input &&
        chain_input->image.width == working.width && chain_input->image.height == working.height;
    if (is_deferred || ((chain || tail_into_resample) && !(state.valid && state.key == key))) {
      if (!chain) {
        chain = std::make_shared<FusedChain>();
        chain->input = input_refs[0];
        if (!chain->input) {
          return make_error("node '" + id + "' (" + type->name + "): input '" +
                            type->inputs[0].name + "' has no image");
        }
      }
      if (state.instance == nullptr) {
        state.instance = type->desc->create(&impl_->host);
        if (state.instance == nullptr) {
          return make_error("node '" + id + "' (" + type->name +
                            "): the plugin could not create the node (out of memory?)");
        }
      }
      auto stage = std::make_unique<FusedChain::Stage>();
      stage->type = type;
      stage->instance = state.instance;
      stage->params = std::move(params);
      stage->strings = std::move(strings);
      stage->inputs = std::move(inputs);
      stage->call.impl = impl_.get();
      stage->call.state = &state;
      stage->call.node_id = id;
      fill_process_ctx(stage->ctx, &impl_->host, context_.generation(), stage->call, stage->inputs,
                       stage->params, settings, format, time, options.frame, working);
      chain->stages.push_back(std::move(stage));
    }
    if (is_deferred) {
      for (auto& image : state.images) image.reset();
      state.valid = false;
      state.key = key;
      chains[id] = chain;
      NodeTiming timing{id, type->name, 0, 0, false};
      timing.fused = true;
      timings_.push_back(timing);
    } else if (state.valid && state.key == key) {
      timings_.push_back(NodeTiming{id, type->name, 0, 0, true});
    } else if (chain) {
      const int width = tail_into_resample ? settings.width : chain->input->image.width;
      const int height = tail_into_resample ? settings.height : chain->input->image.height;
      if (options.finish_each_node) glFinish();
      if (options.measure_gpu_time) state.mark_start();
      auto start = std::chrono::steady_clock::now();
      std::vector<FusedStage> stages;
      for (auto& stage : chain->stages) {
        stages.push_back(FusedStage{stage->type->fusable, stage->instance, &stage->ctx});
      }
      auto fused = impl_->fuser.run(impl_->shaders, impl_->pool, stages, chain->input, width,
                                    height, format);
      if (options.finish_each_node) glFinish();
      auto end = std::chrono::steady_clock::now();
      if (options.measure_gpu_time) state.mark_end();
      impl_->reset_gl_state();
      ++run_counts_[id];
      std::string errors;
      for (auto& stage : chain->stages) {
        if (!stage->call.error.empty()) {
          errors += "node '" + stage->call.node_id + "' (" + stage->type->name +
                    "): " + stage->call.error + "\n";
        }
      }
      if (!fused.ok() || !errors.empty()) {
        state.valid = false;
        return make_error(errors.empty() ? "node '" + id + "' (" + type->name +
                                               "), fused pass: " + fused.message()
                                         : errors.substr(0, errors.size() - 1));
      }
      for (auto& image : state.images) image.reset();
      state.images[0] = *fused;
      state.key = key;
      state.valid = true;
      NodeTiming timing{id, type->name, 0,
                        std::chrono::duration<double, std::milli>(end - start).count(), false};
      if (options.measure_gpu_time) timing.gpu_ms = state.marked_gpu_ms();
      timings_.push_back(timing);
    } else {
      CallState call;
      call.impl = impl_.get();
      call.state = &state;
      call.node_id = id;
      call.input_refs = &input_refs;
      aq_process_ctx ctx{};
      fill_process_ctx(ctx, &impl_->host, context_.generation(), call, inputs, params, settings,
                       format, time, options.frame, working);
      if (!input_lists.empty()) ctx.input_lists = input_lists.data();

      for (auto& image : state.images) image.reset();
      for (auto& scene : state.scenes) scene = nullptr;
      if (options.finish_each_node) glFinish();  // earlier nodes' work is not this node's
      if (options.measure_gpu_time) state.mark_start();
      auto start = std::chrono::steady_clock::now();
      int status = AQ_OK;
      if (type->desc == nullptr) {
        status = run_builtin(*type, state.builtin, ctx, options, impl_->pool, &state.images,
                             &call.error);
      } else {
        if (state.instance == nullptr) {
          state.instance = type->desc->create(&impl_->host);
          if (state.instance == nullptr) {
            return make_error("node '" + id + "' (" + type->name +
                              "): the plugin could not create the node (out of memory?)");
          }
        }
        status = type->desc->process(state.instance, &ctx);
      }
      if (options.finish_each_node) glFinish();
      auto end = std::chrono::steady_clock::now();
      if (options.measure_gpu_time) state.mark_end();
      impl_->reset_gl_state();
      call.scratch.clear();
      NodeTiming timing{id, type->name, 0,
                        std::chrono::duration<double, std::milli>(end - start).count(), false};
      if (options.measure_gpu_time) timing.gpu_ms = state.marked_gpu_ms();
      timings_.push_back(timing);
      ++run_counts_[id];
      if (status != AQ_OK || !call.error.empty()) {
        state.valid = false;
        for (auto& image : state.images) image.reset();
        return make_error("node '" + id + "' (" + type->name +
                          "): " + (call.error.empty() ? "failed without a message" : call.error));
      }
      for (size_t o = 0; o < type->outputs.size(); ++o) {
        bool missing =
            type->outputs[o].type == AQ_PORT_IMAGE ? !state.images[o] : state.scenes[o] == nullptr;
        if (missing) {
          state.valid = false;
          return make_error("node '" + id + "' (" + type->name + "): produced no output '" +
                            type->outputs[o].name + "' (a plugin bug: report it to its author)");
        }
      }
      state.key = key;
      state.valid = true;
    }

    // A node varies over time when it or anything upstream is time-dependent.
    bool node_varies = type->time_dependent();
    for (const auto& [port, source] : node.inputs) node_varies = node_varies || varies[source.node];
    varies[id] = node_varies;

    // Inputs read for the last time go back to the pool, except static results that the next
    // frame will reuse.
    if (!options.retain_outputs) {
      for (const auto& [port, source] : node.inputs) {
        if (--readers[source.node] == 0 &&
            !(options.retain_static_outputs && !varies[source.node])) {
          NodeState& producer = impl_->states[source.node];
          for (auto& image : producer.images) image.reset();
          producer.valid = false;
        }
      }
    }
  }

  NodeState& last = impl_->states[target->node];
  int index = last.type->output_index(target->port);
  if (index < 0) {
    return make_error("output '" + target->str() + "': node '" + target->node + "' (" +
                      last.type->name + ") has no output port '" + target->port + "'");
  }
  if (last.type->outputs[index].type != AQ_PORT_IMAGE) {
    return make_error("output '" + target->str() +
                      "' is a scene, not an image: render an "
                      "image port, e.g. a gbuffer or cel_light output");
  }
  TextureRef result = last.images[index];
  if (!options.retain_outputs && !(options.retain_static_outputs && !varies[target->node])) {
    for (auto& image : last.images) image.reset();
    last.valid = false;
  }
  // A proxy render's output (working size) goes back to the graph's size.
  if (result && result->image.width == working.width && result->image.height == working.height) {
    const uint32_t out_format = result->image.format;
    const bool filterable = out_format == AQ_FORMAT_RGBA16F || out_format == AQ_FORMAT_RGBA32F ||
                            out_format == AQ_FORMAT_R32F;
    if (!filterable || (working.width == settings.width && working.height == settings.height)) {
      return result;  // ids and depth stay at the working size: they cannot be filtered
    }
    auto resampled = impl_->fuser.run(impl_->shaders, impl_->pool, {}, result, settings.width,
                                      settings.height, out_format);
    impl_->reset_gl_state();
    if (!resampled.ok())
      return make_error("resampling the output to the graph's size: " + resampled.message());
    return *resampled;
  }
  return result;
}

}  // namespace aq
