// The node's key and its inputs (node_call.h).
#include "node_call.h"

#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/quality.h>

#include <algorithm>

#include "builtin_nodes.h"
#include "hash.h"

namespace aq {

FrameConstants frame_constants(const Graph& graph, const Plan& plan, const EvalOptions& options,
                               const aq_host* host, uint32_t gl_generation) {
  FrameConstants frame;
  frame.settings = &graph.settings;
  frame.options = &options;
  frame.host = host;
  frame.gl_generation = gl_generation;
  frame.format = plan.format;
  frame.working = plan.working;
  frame.time = (options.frame - graph.settings.first_frame) / std::max(graph.settings.fps, 1e-6);
  if (!graph.source_path.empty())
    frame.graph_dir = std::filesystem::path(graph.source_path).parent_path();
  return frame;
}

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

namespace {

// The NUL check: the ABI passes C strings, so the part before a NUL would be used silently.
Status check_strings(const std::string& id, const NodeType& type, const ParamValues& values) {
  for (size_t p = 0; p < type.params.size(); ++p) {
    if (values.strings[p].find('\0') != std::string::npos) {
      return make_error("node '" + id + "' (" + type.name + "), parameter '" + type.params[p].name +
                        "': the value contains a NUL character; remove it");
    }
  }
  return Ok{};
}

// What the frame adds to a node's key: the graph's size, the working format, the quality, the
// frame for time-dependent nodes, how the plan stores its outputs, and a built-in's own inputs.
uint64_t hash_frame(uint64_t key, const PlannedNode& planned, const FrameConstants& frame,
                    const std::vector<aq_param_value>& params, bool with_frame = true) {
  const Settings& settings = *frame.settings;
  key = hash_value(key, settings.width);
  key = hash_value(key, settings.height);
  key = hash_value(key, frame.format);
  key = hash_value(key, quality_index(settings.quality));
  if (with_frame && planned.type->time_dependent()) key = hash_value(key, frame.options->frame);
  for (uint32_t stored : planned.stored_formats) key = hash_value(key, stored);
  for (bool deferrable : planned.axis_deferrable) key = hash_value(key, deferrable ? 1 : 2);
  // An output left unwritten while unread must be written when a reader appears.
  for (bool read : planned.outputs_read) key = hash_value(key, read ? 3 : 4);
  return builtin_key(*planned.type, params, *frame.options, key);
}

}  // namespace

Result<NodeCall> prepare_node_call(const PlannedNode& planned, const Node& node,
                                   const FrameConstants& frame,
                                   std::map<std::string, NodeState>& states) {
  const NodeType& type = *planned.type;
  NodeCall call;
  uint64_t key = hash_string(kHashSeed, type.name);
  call.params = convert_params(node, type, frame.graph_dir, &key);
  if (auto checked = check_strings(planned.id, type, call.params); !checked.ok())
    return checked.error();
  uint64_t self_key = key;  // without the inputs (damage tracking)
  auto gathered = gather_inputs(planned.id, node, type, states, &key);
  if (!gathered.ok()) return gathered.error();
  call.inputs = std::move(*gathered);
  // Which inputs are connected is the node's own business too: a node reads (and asks the
  // damage of) only those it has.
  for (const aq_input_value& value : call.inputs.values)
    self_key = hash_value(self_key, value.connected);
  call.key = hash_frame(key, planned, frame, call.params.params);
  call.self_key = hash_frame(self_key, planned, frame, call.params.params);
  call.damage_key = hash_frame(self_key, planned, frame, call.params.params, /*with_frame=*/false);
  return call;
}

void fill_process_ctx(aq_process_ctx& ctx, const FrameConstants& frame, CallState& call,
                      std::vector<aq_input_value>& inputs, std::vector<aq_param_value>& params) {
  const Settings& settings = *frame.settings;
  ctx.struct_size = sizeof(aq_process_ctx);
  ctx.host = frame.host;
  ctx.host_data = &call;
  ctx.node_id = call.node_id.c_str();
  ctx.inputs = inputs.data();
  ctx.input_count = static_cast<uint32_t>(inputs.size());
  ctx.params = params.data();
  ctx.param_count = static_cast<uint32_t>(params.size());
  ctx.width = frame.working.width;
  ctx.height = frame.working.height;
  ctx.precision = settings.precision == "float" ? AQ_PRECISION_FLOAT : AQ_PRECISION_HALF;
  ctx.working_format = frame.format;
  ctx.time = frame.time;
  ctx.frame = frame.options->frame;
  ctx.fps = settings.fps;
  ctx.gl_generation = frame.gl_generation;
  ctx.quality = quality_index(settings.quality);
  ctx.render_scale = render_scale(settings.quality);
  ctx.input_lists = nullptr;
  ctx.input_keys = nullptr;
}

}  // namespace aq
