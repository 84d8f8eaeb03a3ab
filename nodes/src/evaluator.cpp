// Evaluator: execution of an evaluation plan (plan.h: cull, sort, readers, fusion, sizes),
// with per-node cache keys, texture release after the last reader, and GPU timing. The host
// services a plugin calls live in host_services.cpp; pointwise fusion's shader in
// pointwise_fusion.cpp.
#include <aquarelle/core/evaluator.h>

#include <aquarelle/core/bypass.h>
#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/plan.h>
#include <aquarelle/core/quality.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "builtin_nodes.h"
#include "hash.h"
#include "host_services.h"
#include "pointwise_fusion.h"
#include "shader_cache.h"

namespace aq {

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
    std::vector<TextureRef> input_refs;  // held: extra inputs are read when the chain runs
    std::vector<uint64_t> input_keys;
    std::vector<DamageSource> sources;
    CallState call;
    aq_process_ctx ctx{};
  };
  // An epilogue producer (PlannedNode::producer): the node whose process() the chain's pass
  // runs, applying the stages in its last draw, instead of reading `input`.
  struct Producer {
    const NodeType* type = nullptr;
    NodeState* state = nullptr;
    std::vector<aq_param_value> params;
    std::vector<std::string> strings;
    std::vector<aq_input_value> inputs;
    std::vector<TextureRef> input_refs;  // held: nothing reuses them before the node runs
    std::vector<uint64_t> input_keys;
    std::vector<DamageSource> sources;
    std::vector<std::vector<aq_input_value>> links;
    std::vector<aq_input_list> lists;
    CallState call;
    aq_process_ctx ctx{};
  };
  TextureRef input;  // the image the first stage reads
  std::unique_ptr<Producer> producer;
  std::vector<std::unique_ptr<Stage>> stages;
};

namespace {

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
  ctx.input_keys = nullptr;
}

// The format a fused pass writes a chain's result in: 8-bit HDR where the plan stores the chain's
// last node's output so for readers that decode it (the fused pass encodes), else `working`.
uint32_t chain_result_format(const std::vector<uint32_t>& stored, uint32_t working) {
  return !stored.empty() && stored[0] == AQ_FORMAT_RGBA8_HDR ? stored[0] : working;
}

// A node's parameters as the ABI passes them; `strings` owns what params[i].s points to.
struct ParamValues {
  std::vector<aq_param_value> params;
  std::vector<std::string> strings;
};

// Converts the node's parameters (defaults for missing ones) and hashes them into `key`.
ParamValues convert_params(const Node& node, const NodeType& type,
                           const std::filesystem::path& graph_dir, uint64_t* key) {
  ParamValues values;
  values.params.resize(type.params.size());
  values.strings.resize(type.params.size());
  for (size_t p = 0; p < type.params.size(); ++p) {
    const ParamInfo& info = type.params[p];
    nlohmann::json value = param_value_or_default(node, info);
    // replace, not throw, on invalid UTF-8 from --set or the editor
    *key = hash_string(*key, value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
    aq_param_value& out = values.params[p];
    out = aq_param_value{{0, 0, 0}, 0, nullptr};
    switch (info.type) {
      case AQ_PARAM_FLOAT:
        out.f[0] = value.is_number() ? value.get<double>() : info.default_value[0];
        break;
      case AQ_PARAM_INT:
        out.i =
            value.is_number() ? value.get<int64_t>() : static_cast<int64_t>(info.default_value[0]);
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
        std::string& text = values.strings[p];
        text = value.is_string() ? value.get<std::string>() : info.default_string;
        if (info.type == AQ_PARAM_PATH && !text.empty() &&
            std::filesystem::path(text).is_relative() && !graph_dir.empty()) {
          text = (graph_dir / text).lexically_normal().string();
        }
        out.s = text.c_str();
        break;
      }
    }
  }
  return values;
}

// A node's inputs as the ABI passes them, and the textures behind its image inputs.
struct GatheredInputs {
  std::vector<aq_input_value> values;
  std::vector<uint64_t> keys;         // per input (aq_process_ctx::input_keys); 0 unconnected
  std::vector<TextureRef> images;     // per input; empty for scenes and unconnected inputs
  std::vector<DamageSource> sources;  // per input (aq_host::input_damage)
  // Every link of each input, for nodes with an AQ_PORT_MULTI port (ctx.input_lists); empty
  // otherwise. `lists` points into `links` (and into `values` for single-link inputs).
  std::vector<std::vector<aq_input_value>> links;
  std::vector<aq_input_list> lists;
};

// The one place that turns a node's links into its inputs (checking that each names an output
// of the right type) and hashes its sources' keys into `key`.
Result<GatheredInputs> gather_inputs(const std::string& id, const Node& node, const NodeType& type,
                                     std::map<std::string, NodeState>& states, uint64_t* key) {
  GatheredInputs gathered;
  gathered.values.resize(type.inputs.size());
  gathered.keys.assign(type.inputs.size(), 0);
  gathered.images.resize(type.inputs.size());
  gathered.sources.resize(type.inputs.size());
  for (size_t i = 0; i < type.inputs.size(); ++i) {
    const PortInfo& port = type.inputs[i];
    aq_input_value& in = gathered.values[i];
    in = aq_input_value{static_cast<uint32_t>(port.type), 0, {0, 0, 0, 0}, nullptr};
    if (port.multi) {  // every link, in graph order (multi ports are scene ports)
      gathered.links.resize(type.inputs.size());
      auto [first, last] = node.inputs.equal_range(port.name);
      for (auto link = first; link != last; ++link) {
        NodeState& source = states[link->second.node];
        const int index =
            source.type != nullptr ? source.type->output_index(link->second.port) : -1;
        if (index < 0 || source.type->outputs[index].type != AQ_PORT_SCENE) {
          return make_error("node '" + id + "', input '" + port.name + "': '" + link->second.str() +
                            "' is not a scene output");
        }
        *key = hash_value(*key, source.key);
        *key = hash_string(*key, link->second.port);
        const uint64_t before = gathered.keys[i] == 0 ? kHashSeed : gathered.keys[i];
        gathered.keys[i] = hash_string(hash_value(before, source.key), link->second.port);
        gathered.links[i].push_back(
            aq_input_value{AQ_PORT_SCENE, 1, {0, 0, 0, 0}, source.scenes[index]});
      }
      *key = hash_value(*key, gathered.links[i].size());
      if (!gathered.links[i].empty()) in = gathered.links[i][0];
      continue;
    }
    auto link = node.inputs.find(port.name);
    if (link == node.inputs.end()) {
      if (!port.optional) {
        return make_error("node '" + id + "' (" + type.name + "): required input '" + port.name +
                          "' is not connected");
      }
      *key = hash_string(*key, "-");
      continue;
    }
    NodeState& source = states[link->second.node];
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
    *key = hash_value(*key, source.key);
    *key = hash_string(*key, link->second.port);
    gathered.keys[i] = hash_string(hash_value(kHashSeed, source.key), link->second.port);
    gathered.sources[i] = DamageSource{&source, static_cast<uint32_t>(index), link->second.port};
    in.connected = 1;
    if (port.type == AQ_PORT_IMAGE) {
      gathered.images[i] = source.images[index];
      if (gathered.images[i]) in.image = gathered.images[i]->image;
    } else {
      in.scene = source.scenes[index];
    }
  }
  if (type.has_multi_input()) {
    gathered.links.resize(type.inputs.size());
    for (size_t i = 0; i < gathered.values.size(); ++i) {
      auto& links = gathered.links[i];
      gathered.lists.push_back(
          links.empty() && gathered.values[i].connected != 0
              ? aq_input_list{&gathered.values[i], 1}
              : aq_input_list{links.data(), static_cast<uint32_t>(links.size())});
    }
  }
  return gathered;
}

// Where a fused chain's stages may change its result through their other inputs (each read
// within the stage's reach, aq_pointwise_desc::reach) or their own parameters: what the
// producer must redraw besides its own damage (aq_host::epilogue_damage).
Region epilogue_damage_of(const FusedChain& chain, int width, int height) {
  Region damage;
  for (const auto& stage : chain.stages) {
    const NodeState& state = *stage->call.state;
    if (!state.seen || state.seen_self_key != stage->call.self_key) return Region::everything();
    const aq_pointwise_desc& desc = *stage->type->fusable;
    const bool has_reach =
        desc.struct_size >= offsetof(aq_pointwise_desc, reach) + sizeof(desc.reach);
    const int reach = has_reach ? desc.reach : -1;
    for (uint32_t k = 1; k < stage->inputs.size(); ++k) {
      if (stage->inputs[k].connected == 0) continue;
      const aq_image& side = stage->inputs[k].image;
      const bool same_pixels = side.width == width && side.height == height;
      const Region changed = input_damage_of(stage->call, k);
      if (changed.empty()) continue;
      if (reach < 0 || changed.all() || !same_pixels) return Region::everything();
      damage.add(changed.dilated(reach, reach, width, height));
    }
  }
  return damage;
}

}  // namespace

struct Evaluator::Impl {
  GlContext& context;
  HostServices host;
  PointwiseFuser fuser;
  std::map<std::string, NodeState> states;

  Impl(GlContext& c, TexturePool& p) : context(c), host(c, p) {}
  ~Impl() { destroy_all(); }

  void destroy_state(NodeState& state) {
    if (state.type != nullptr) {
      for (uint32_t o = 0; o < state.type->outputs.size(); ++o)
        host.pool().unclaim(output_writer(state, o));
    }
    state.images.clear();
    state.scenes.clear();
    if (state.instance != nullptr && state.type != nullptr && state.type->desc != nullptr) {
      state.type->desc->destroy(state.instance);
    }
    state.instance = nullptr;
    state.valid = false;
    state.seen = false;
    state.writer_tag = 0;  // a new instance gets a new tag (aq_host::output_kept)
  }
  void destroy_all() {
    if (!states.empty()) context.activate();
    for (auto& [id, state] : states) destroy_state(state);
    states.clear();
  }

  // Epilogue fusion: runs the producer's process() with `stages` as the epilogue of the draw
  // that writes its output 0, which becomes the chain's result (stored as the chain's last
  // node's output is: `stored`). A producer that applied no epilogue (it passed its input
  // through, or its method's shaders do not call aq_epilogue) gets the chain as a pass of its
  // own, so the result never depends on whether the node cooperated.
  Result<TextureRef> run_producer(FusedChain::Producer& producer,
                                  const std::vector<FusedStage>& stages,
                                  const std::vector<uint32_t>& stored, uint32_t format) {
    NodeState& state = *producer.state;
    CallState& call = producer.call;
    call.stored_formats = &stored;
    call.epilogue = &stages;
    call.epilogue_draws = 0;
    call.error.clear();
    begin_damage_call(call, producer.type->outputs.size());
    for (auto& image : state.images) image.reset();
    for (auto& scene : state.scenes) scene = nullptr;
    const int status = producer.type->desc->process(state.instance, &producer.ctx);
    unbind_stage_samplers(stages);
    HostServices::reset_gl_state();
    call.scratch.clear();
    TextureRef out = state.images.empty() ? TextureRef() : state.images[0];
    for (auto& image : state.images) image.reset();
    state.valid = false;
    const std::string where = "node '" + call.node_id + "' (" + producer.type->name + ")";
    if (status != AQ_OK || !call.error.empty())
      return make_error(where + ": " +
                        (call.error.empty() ? "failed without a message" : call.error));
    if (!out)
      return make_error(where + ": produced no output '" + producer.type->outputs[0].name +
                        "' (a plugin bug: report it to its author)");
    if (call.epilogue_draws > 0) return out;
    return fuser.run(host.shaders(), host.pool(), stages, out, out->image.width, out->image.height,
                     chain_result_format(stored, format));
  }
};

Evaluator::Evaluator(GlContext& context, const Registry& registry)
    : context_(context), registry_(registry), pool_(std::make_unique<TexturePool>()) {
  context_.activate();
  impl_ = std::make_unique<Impl>(context_, *pool_);
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
  impl_->host.shaders().set_hot_reload(enabled);
}

int readback_rows_per_band(int width, int bytes_per_pixel, int64_t max_bytes) {
  const int64_t row = static_cast<int64_t>(std::max(width, 1)) * std::max(bytes_per_pixel, 1);
  return static_cast<int>(std::clamp<int64_t>(max_bytes / row, 1, std::numeric_limits<int>::max()));
}

// aquarelle/hdr8.glsl's aq_hdr8_decode on the CPU: rgb c = e² / (1 − e²), alpha as stored.
static void decode_hdr8(std::vector<float>& rgba) {
  for (size_t i = 0; i + 3 < rgba.size(); i += 4) {
    for (size_t c = 0; c < 3; ++c) {
      const float y = rgba[i + c] * rgba[i + c];
      rgba[i + c] = y / std::max(1.0f - y, 1.0f / 256.0f);
    }
  }
}

// An AQ_FORMAT_RGBA8_HDR_BLOCKS texture's pixels, decoded (plugin.h has the layout).
static Result<ImageF> read_blocks(GLuint texture, int width, int height) {
  const int blocks_x = (width + 1) / 2, blocks_y = (height + 1) / 2;
  std::vector<uint32_t> words(static_cast<size_t>(blocks_x) * blocks_y * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureSubImage(texture, 0, 0, 0, 0, blocks_x, blocks_y, 1, GL_RGBA_INTEGER, GL_UNSIGNED_INT,
                       static_cast<GLsizei>(words.size() * 4), words.data());
  if (glGetError() != GL_NO_ERROR) return make_error("reading a texture of 2 x 2 blocks failed");
  ImageF out(width, height, 4);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const size_t block = (static_cast<size_t>(y / 2) * blocks_x + x / 2) * 4;
      const uint32_t word = words[block + (y % 2) * 2 + x % 2];
      for (int c = 0; c < 4; ++c)
        out.pixels[(static_cast<size_t>(y) * width + x) * 4 + c] =
            static_cast<float>((word >> (8 * c)) & 0xFFu) / 255.0f;
    }
  }
  decode_hdr8(out.pixels);
  return out;
}

Result<ImageF> read_texture(GLuint texture, int width, int height, uint32_t format,
                            int64_t max_bytes_per_read) {
  if (format == AQ_FORMAT_RGBA8_HDR_BLOCKS) {
    while (glGetError() != GL_NO_ERROR) {
    }
    return read_blocks(texture, width, height);
  }
  bool single =
      format == AQ_FORMAT_R32F || format == AQ_FORMAT_DEPTH32F || format == AQ_FORMAT_R32UI;
  const int channels = single ? 1 : 4;
  ImageF out(width, height, channels);
  while (glGetError() != GL_NO_ERROR) {
  }  // only this read's error counts below
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  const bool words = format == AQ_FORMAT_RGBA32UI;  // packed data: the words' values
  const bool ids = format == AQ_FORMAT_R32UI || words;
  const GLenum gl_format =
      words ? GL_RGBA_INTEGER
      : ids ? GL_RED_INTEGER
            : (format == AQ_FORMAT_DEPTH32F ? GL_DEPTH_COMPONENT : (single ? GL_RED : GL_RGBA));
  const GLenum gl_type = ids ? GL_UNSIGNED_INT : GL_FLOAT;
  // The buffer size of one read is a GLsizei: a 16384x16384 RGBA float image (4 GiB) does not
  // fit, so large textures are read in bands of rows, each well under 2 GiB.
  const int pixel_bytes = channels * 4;
  const int band = readback_rows_per_band(width, pixel_bytes, max_bytes_per_read);
  std::vector<uint32_t> id_rows;
  for (int y = 0; y < height; y += band) {
    const int rows = std::min(band, height - y);
    const size_t offset = static_cast<size_t>(y) * width * channels;
    const auto bytes = static_cast<GLsizei>(static_cast<int64_t>(rows) * width * pixel_bytes);
    void* target = out.pixels.data() + offset;
    if (ids) {
      id_rows.resize(static_cast<size_t>(rows) * width * channels);
      target = id_rows.data();
    }
    glGetTextureSubImage(texture, 0, 0, y, 0, width, rows, 1, gl_format, gl_type, bytes, target);
    if (ids) {
      for (size_t i = 0; i < id_rows.size(); ++i) {
        out.pixels[offset + i] = static_cast<float>(id_rows[i]);
      }
    }
  }
  if (GLenum error = glGetError(); error != GL_NO_ERROR) {
    char text[96];
    std::snprintf(text, sizeof(text), "reading the texture back failed (GL error 0x%04X)", error);
    return make_error(text);
  }
  if (format == AQ_FORMAT_RGBA8_HDR) decode_hdr8(out.pixels);
  return out;
}

Result<ImageF> Evaluator::read_back(const TextureRef& texture) {
  if (!texture) return make_error("nothing to read back");
  context_.activate();
  const aq_image& image = texture->image;
  return read_texture(image.texture, image.width, image.height, image.format);
}

// AQUARELLE_FORMATS_BY_NEED=0 keeps every output in the format its plugin asks for,
// AQUARELLE_HDR8=0 only turns the encoded HDR formats off, AQUARELLE_MORPH_BLOCKS=0 only the one
// in 2 x 2 blocks, AQUARELLE_DEFER_AXIS=0 keeps a separable filter's last 1D pass in its own
// node, and AQUARELLE_EPILOGUE_FUSION=0 runs
// pointwise chains after an AQ_NODE_EPILOGUE node as a pass of their own, so a bench run can
// measure each lever off without a rebuild (the bench sets no EvalOptions for them).
static bool enabled_in_environment(const char* name) {
  const char* value = std::getenv(name);
  return value == nullptr || std::string(value) != "0";
}

namespace {

Result<Plan> compile(const Graph& graph, const Registry& registry, const EvalOptions& options,
                     const std::optional<PortRef>& output) {
  PlanOptions plan_options;
  plan_options.fuse_pointwise = options.fuse_pointwise;
  plan_options.retain_static_outputs = options.retain_outputs || options.retain_static_outputs;
  plan_options.formats_by_need =
      options.formats_by_need && enabled_in_environment("AQUARELLE_FORMATS_BY_NEED");
  plan_options.hdr8 = plan_options.formats_by_need && enabled_in_environment("AQUARELLE_HDR8");
  plan_options.blocks = plan_options.hdr8 && enabled_in_environment("AQUARELLE_MORPH_BLOCKS");
  plan_options.defer_axis = plan_options.blocks && enabled_in_environment("AQUARELLE_DEFER_AXIS");
  plan_options.epilogue_fusion = enabled_in_environment("AQUARELLE_EPILOGUE_FUSION");
  return compile_plan(graph, registry, plan_options, output);
}

}  // namespace

Result<Plan> Evaluator::plan(const Graph& given_graph, const EvalOptions& options,
                             const std::optional<PortRef>& given_output) const {
  auto bypassed = bypassed_graph(given_graph, registry_, given_output);  // bypass.h
  if (!bypassed.ok()) return bypassed.error();
  return compile(bypassed->graph(given_graph), registry_, options, bypassed->output);
}

Result<TextureRef> Evaluator::evaluate(const Graph& given_graph, const EvalOptions& options,
                                       const std::optional<PortRef>& given_requested) {
  timings_.clear();
  auto bypassed = bypassed_graph(given_graph, registry_, given_requested);  // bypass.h
  if (!bypassed.ok()) return bypassed.error();
  const Graph& graph = bypassed->graph(given_graph);
  const std::optional<PortRef>& requested = bypassed->output;
  if (!context_.activate()) return make_error("the OpenGL context cannot be made current");
  impl_->host.make_current();
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

  auto compiled = compile(graph, registry_, options, requested);  // bypass already applied
  if (!compiled.ok()) return compiled.error();
  const Plan& plan = *compiled;
  const PortRef& target = plan.output;

  // Readers left per producer, so outputs go back to the pool after their last use.
  std::map<std::string, int> readers;
  std::map<std::string, bool> varies;
  for (const auto& planned : plan.nodes) {
    readers[planned.id] = planned.readers;
    varies[planned.id] = planned.varies;
  }
  // The stages of each fused chain so far, by the id of its last deferred node.
  std::map<std::string, std::shared_ptr<FusedChain>> chains;
  const Settings& settings = graph.settings;
  const uint32_t format = plan.format;
  const double time = (options.frame - settings.first_frame) / std::max(settings.fps, 1e-6);
  const PixelSize working = plan.working;
  std::filesystem::path graph_dir = graph.source_path.empty()
                                        ? std::filesystem::path()
                                        : std::filesystem::path(graph.source_path).parent_path();
  const aq_host* host = impl_->host.table();

  for (const PlannedNode& planned : plan.nodes) {
    const std::string& id = planned.id;
    const Node& node = graph.nodes.at(id);
    const NodeType* type = planned.type;
    NodeState& state = impl_->states[id];
    state.type = type;
    if (state.images.size() != type->outputs.size()) {
      state.images.assign(type->outputs.size(), nullptr);
      state.scenes.assign(type->outputs.size(), nullptr);
      state.valid = false;
    }

    uint64_t key = kHashSeed;
    key = hash_string(key, type->name);
    ParamValues param_values = convert_params(node, *type, graph_dir, &key);
    for (size_t p = 0; p < type->params.size(); ++p) {
      if (param_values.strings[p].find('\0') != std::string::npos) {
        // The ABI passes C strings: the part before the NUL would be used silently.
        return make_error("node '" + id + "' (" + type->name + "), parameter '" +
                          type->params[p].name +
                          "': the value contains a NUL character; remove it");
      }
    }
    std::vector<aq_param_value>& params = param_values.params;
    uint64_t self_key = key;  // without the inputs (damage tracking)
    auto gathered = gather_inputs(id, node, *type, impl_->states, &key);
    if (!gathered.ok()) return gathered.error();
    std::vector<aq_input_value>& inputs = gathered->values;
    std::vector<TextureRef>& input_refs = gathered->images;
    // Which inputs are connected is the node's own business too: a node reads (and asks the
    // damage of) only those it has.
    for (const aq_input_value& value : inputs) self_key = hash_value(self_key, value.connected);
    for (uint64_t* k : {&key, &self_key}) {
      *k = hash_value(*k, settings.width);
      *k = hash_value(*k, settings.height);
      *k = hash_value(*k, format);
      *k = hash_value(*k, quality_index(settings.quality));
      if (type->time_dependent()) *k = hash_value(*k, options.frame);
      for (uint32_t stored : planned.stored_formats) *k = hash_value(*k, stored);
      for (bool deferrable : planned.axis_deferrable) *k = hash_value(*k, deferrable ? 1 : 2);
      *k = builtin_key(*type, params, options, *k);
    }

    // Fusion: a deferred node only records its stage; the node reading it runs the chain.
    std::shared_ptr<FusedChain> chain;
    if (type->fusable != nullptr && node.inputs.count(type->inputs[0].name) != 0) {
      const std::string& source = node.inputs.at(type->inputs[0].name).node;
      if (auto found = chains.find(source); found != chains.end()) {
        chain = found->second;
        chains.erase(found);
      }
    }
    const bool is_deferred = planned.deferred;
    // The output's pointwise tail runs in the pass that resamples a proxy render's output.
    // Nodes without inputs (image_input, generators) have no input_refs[0].
    const TextureRef chain_input =
        chain ? chain->input : (input_refs.empty() ? TextureRef() : input_refs[0]);
    const PlannedPass* pass = is_deferred ? nullptr : plan.pass_of(id);
    const bool tail_into_resample = pass != nullptr && pass->resamples && chain_input &&
                                    chain_input->image.width == working.width &&
                                    chain_input->image.height == working.height;
    if (planned.producer) {
      if (state.instance == nullptr && type->desc != nullptr) {
        state.instance = type->desc->create(host);
        if (state.instance == nullptr) {
          return make_error("node '" + id + "' (" + type->name +
                            "): the plugin could not create the node (out of memory?)");
        }
      }
      chain = std::make_shared<FusedChain>();
      chain->producer = std::make_unique<FusedChain::Producer>();
      FusedChain::Producer& producer = *chain->producer;
      producer.type = type;
      producer.state = &state;
      producer.params = std::move(params);
      producer.strings = std::move(param_values.strings);
      producer.inputs = std::move(inputs);
      producer.input_refs = std::move(input_refs);
      producer.links = std::move(gathered->links);
      producer.lists = std::move(gathered->lists);
      producer.call.host = &impl_->host;
      producer.call.state = &state;
      producer.call.node_id = id;
      producer.call.input_refs = &producer.input_refs;
      producer.call.working_format = format;
      fill_process_ctx(producer.ctx, host, context_.generation(), producer.call, producer.inputs,
                       producer.params, settings, format, time, options.frame, working);
      if (!producer.lists.empty()) producer.ctx.input_lists = producer.lists.data();
      producer.input_keys = gathered->keys;
      producer.ctx.input_keys = producer.input_keys.data();
      producer.sources = gathered->sources;
      producer.call.sources = &producer.sources;
      producer.call.input_keys = &producer.input_keys;
      producer.call.self_key = self_key;
    } else if (is_deferred ||
               ((chain || tail_into_resample) && !(state.valid && state.key == key))) {
      if (!chain) {
        chain = std::make_shared<FusedChain>();
        chain->input = input_refs[0];
        if (!chain->input) {
          return make_error("node '" + id + "' (" + type->name + "): input '" +
                            type->inputs[0].name + "' has no image");
        }
      }
      if (state.instance == nullptr) {
        state.instance = type->desc->create(host);
        if (state.instance == nullptr) {
          return make_error("node '" + id + "' (" + type->name +
                            "): the plugin could not create the node (out of memory?)");
        }
      }
      auto stage = std::make_unique<FusedChain::Stage>();
      stage->type = type;
      stage->instance = state.instance;
      stage->params = std::move(params);
      stage->strings = std::move(param_values.strings);
      stage->inputs = std::move(inputs);
      stage->input_refs = input_refs;
      stage->call.host = &impl_->host;
      stage->call.state = &state;
      stage->call.node_id = id;
      fill_process_ctx(stage->ctx, host, context_.generation(), stage->call, stage->inputs,
                       stage->params, settings, format, time, options.frame, working);
      stage->input_keys = gathered->keys;
      stage->ctx.input_keys = stage->input_keys.data();
      stage->sources = gathered->sources;
      stage->call.sources = &stage->sources;
      stage->call.input_keys = &stage->input_keys;
      stage->call.self_key = self_key;
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
      if (options.finish_each_node) glFinish();
      if (options.measure_gpu_time) state.mark_start();
      auto start = std::chrono::steady_clock::now();
      std::vector<FusedStage> stages;
      for (auto& stage : chain->stages) {
        FusedStage fused_stage{stage->type->fusable, stage->instance, &stage->ctx, {}};
        for (size_t k = 1; k < stage->inputs.size(); ++k)
          fused_stage.samplers.emplace_back(stage->type->inputs[k].name,
                                            stage->inputs[k].image.texture);
        stages.push_back(std::move(fused_stage));
      }
      Result<TextureRef> fused = make_error("no fused pass ran");
      const uint64_t previous_key = state.key;
      if (chain->producer) {
        chain->producer->call.epilogue_damage =
            epilogue_damage_of(*chain, working.width, working.height);
        // What the producer's kept output holds depends on the epilogue it applied.
        uint64_t& producer_key = chain->producer->call.self_key;
        producer_key = hash_string(producer_key, "epilogue");
        for (const auto& stage : chain->stages)
          producer_key = hash_string(producer_key, stage->call.node_id);
        fused = impl_->run_producer(*chain->producer, stages, planned.stored_formats, format);
      } else {
        const int width = tail_into_resample ? settings.width : chain->input->image.width;
        const int height = tail_into_resample ? settings.height : chain->input->image.height;
        fused =
            impl_->fuser.run(impl_->host.shaders(), impl_->host.pool(), stages, chain->input, width,
                             height, chain_result_format(planned.stored_formats, format));
      }
      if (options.finish_each_node) glFinish();
      auto end = std::chrono::steady_clock::now();
      if (options.measure_gpu_time) state.mark_end();
      HostServices::reset_gl_state();
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
        state.seen = false;  // what a failed call left in kept outputs is unknown
        if (chain->producer) chain->producer->state->seen = false;
        for (auto& stage : chain->stages) stage->call.state->seen = false;
        return make_error(errors.empty() ? "node '" + id + "' (" + type->name +
                                               "), fused pass: " + fused.message()
                                         : errors.substr(0, errors.size() - 1));
      }
      for (auto& image : state.images) image.reset();
      state.images[0] = *fused;
      state.key = key;
      state.valid = true;
      // What each stage saw; the chain's result changed where its producer redrew.
      for (auto& stage : chain->stages)
        finish_damage_call(*stage->call.state, stage->call, stage->call.state->key);
      std::vector<std::optional<Region>> result_damage;
      if (chain->producer) {
        FusedChain::Producer& producer = *chain->producer;
        finish_damage_call(*producer.state, producer.call, producer.state->key);
        if (!producer.call.declared_damage.empty())
          result_damage.push_back(producer.call.declared_damage[0]);
      }
      record_output_damage(state, previous_key, result_damage, {});
      NodeTiming timing{id, type->name, 0,
                        std::chrono::duration<double, std::milli>(end - start).count(), false};
      if (options.measure_gpu_time) timing.gpu_ms = state.marked_gpu_ms();
      timing.redrawn = state.redrawn;
      timings_.push_back(timing);
    } else {
      CallState call;
      call.host = &impl_->host;
      call.state = &state;
      call.node_id = id;
      call.input_refs = &input_refs;
      call.stored_formats = &planned.stored_formats;
      call.axis_deferrable = &planned.axis_deferrable;
      call.working_format = format;
      call.sources = &gathered->sources;
      call.input_keys = &gathered->keys;
      call.self_key = self_key;
      begin_damage_call(call, type->outputs.size());
      const uint64_t previous_key = state.key;
      aq_process_ctx ctx{};
      fill_process_ctx(ctx, host, context_.generation(), call, inputs, params, settings, format,
                       time, options.frame, working);
      if (!gathered->lists.empty()) ctx.input_lists = gathered->lists.data();
      ctx.input_keys = gathered->keys.data();

      for (auto& image : state.images) image.reset();
      for (auto& scene : state.scenes) scene = nullptr;
      if (options.finish_each_node) glFinish();  // earlier nodes' work is not this node's
      if (options.measure_gpu_time) state.mark_start();
      auto start = std::chrono::steady_clock::now();
      int status = AQ_OK;
      if (type->desc == nullptr) {
        status = run_builtin(*type, state.builtin, ctx, options, impl_->host.pool(), &state.images,
                             &call.error);
      } else {
        if (state.instance == nullptr) {
          state.instance = type->desc->create(host);
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
      HostServices::reset_gl_state();
      call.scratch.clear();
      NodeTiming timing{id, type->name, 0,
                        std::chrono::duration<double, std::milli>(end - start).count(), false};
      if (options.measure_gpu_time) timing.gpu_ms = state.marked_gpu_ms();
      timings_.push_back(timing);
      ++run_counts_[id];
      if (status != AQ_OK || !call.error.empty()) {
        state.valid = false;
        state.seen = false;
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
      // An encoded HDR image reaches only readers that decode it: one a plugin passed through
      // to an output the plan keeps in the working format is decoded here.
      for (size_t o = 0; o < type->outputs.size(); ++o) {
        const TextureRef& image = state.images[o];
        const bool blocks_stored =
            call.stored_format(static_cast<uint32_t>(o)) == AQ_FORMAT_RGBA8_HDR_BLOCKS;
        if (image && (image->image.format == AQ_FORMAT_RGBA8_HDR_BLOCKS) != blocks_stored) {
          state.valid = false;
          return make_error("node '" + id + "' (" + type->name + "): output '" +
                            type->outputs[o].name +
                            "' is not in the 2 x 2 blocks its readers were promised, or is in "
                            "blocks they were not (a plugin bug: report it to its author)");
        }
        if (!image || image->image.format != AQ_FORMAT_RGBA8_HDR ||
            call.stored_format(static_cast<uint32_t>(o)) == AQ_FORMAT_RGBA8_HDR)
          continue;
        auto decoded = impl_->fuser.run(impl_->host.shaders(), impl_->host.pool(), {}, image,
                                        image->image.width, image->image.height, format);
        if (!decoded.ok()) return make_error("node '" + id + "': " + decoded.error().message);
        state.images[o] = *decoded;
      }
      finish_damage_call(state, call, previous_key);
      timings_.back().redrawn = state.redrawn;
      state.key = key;
      state.valid = true;
    }

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

  NodeState& last = impl_->states[target.node];
  int index = last.type->output_index(target.port);
  if (index < 0) {
    return make_error("output '" + target.str() + "': node '" + target.node + "' (" +
                      last.type->name + ") has no output port '" + target.port + "'");
  }
  if (last.type->outputs[index].type != AQ_PORT_IMAGE) {
    return make_error("output '" + target.str() +
                      "' is a scene, not an image: render an "
                      "image port, e.g. a gbuffer or cel_light output");
  }
  TextureRef result = last.images[index];
  if (!options.retain_outputs && !(options.retain_static_outputs && !varies[target.node])) {
    for (auto& image : last.images) image.reset();
    last.valid = false;
  }
  // A proxy render's output (working size) goes back to the graph's size.
  if (result && result->image.width == working.width && result->image.height == working.height) {
    const uint32_t out_format = result->image.format;
    const bool filterable = out_format == AQ_FORMAT_RGBA16F || out_format == AQ_FORMAT_RGBA32F ||
                            out_format == AQ_FORMAT_R32F || out_format == AQ_FORMAT_RGBA8;
    if (!filterable || (working.width == settings.width && working.height == settings.height)) {
      return result;  // ids and depth stay at the working size: they cannot be filtered
    }
    auto resampled = impl_->fuser.run(impl_->host.shaders(), impl_->host.pool(), {}, result,
                                      settings.width, settings.height, out_format);
    HostServices::reset_gl_state();
    if (!resampled.ok())
      return make_error("resampling the output to the graph's size: " + resampled.message());
    return *resampled;
  }
  return result;
}

}  // namespace aq
