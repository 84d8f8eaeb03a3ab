// The registry of node types: copies a plugin's C description into a NodeType after checking
// that it makes sense (names, types, ranges, defaults, entry points), so that everything after
// loading (validator, editor panels, `aquarelle nodes`) can trust the model without re-checking.
#include <aquarelle/core/registry.h>

#include <cstddef>

#include <cmath>
#include <set>
#include <sstream>
#include <string_view>

namespace aq {
namespace {

bool is_type_name(const std::string& name) {
  if (name.empty()) return false;
  for (char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
    if (!ok) return false;
  }
  return true;
}

std::string text_or_empty(const char* text) {
  return text != nullptr ? text : "";
}

std::string format_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

std::vector<std::string> split_enum_values(const std::string& values) {
  std::vector<std::string> names;
  std::string current;
  for (char c : values) {
    if (c == '|') {
      names.push_back(current);
      current.clear();
    } else {
      current += c;
    }
  }
  names.push_back(current);
  return names;
}

bool known_port_type(uint32_t type) {
  return type == AQ_PORT_IMAGE || type == AQ_PORT_SCENE;
}

bool known_param_type(uint32_t type) {
  return type >= AQ_PARAM_FLOAT && type <= AQ_PARAM_VEC3;
}

// Checks one port list; returns the reason it is invalid, or "" when it is fine.
std::string read_ports(const aq_port_desc* ports, uint32_t count, const char* kind,
                       std::vector<PortInfo>* out) {
  if (count > 0 && ports == nullptr) {
    return std::string(kind) + " count is " + std::to_string(count) + " but the array is NULL";
  }
  std::set<std::string> seen;
  for (uint32_t i = 0; i < count; ++i) {
    const aq_port_desc& port = ports[i];
    const std::string where = std::string(kind) + " " + std::to_string(i);
    if (port.name == nullptr) return where + " has no name";
    const std::string name = port.name;
    if (!is_type_name(name)) {
      return where + " is named '" + name + "': port names may hold only a-z, 0-9 and '_'";
    }
    if (!known_port_type(port.type)) {
      return std::string(kind) + " '" + name + "' has unknown port type " +
             std::to_string(port.type) + " (expected AQ_PORT_IMAGE or AQ_PORT_SCENE)";
    }
    if ((port.flags &
         ~static_cast<uint32_t>(AQ_PORT_OPTIONAL | AQ_PORT_MULTI | AQ_PORT_8BIT_ENOUGH |
                                AQ_PORT_HDR8 | AQ_PORT_BLOCKS | AQ_PORT_DEFER_AXIS)) != 0) {
      return std::string(kind) + " '" + name + "' has unknown flags " + std::to_string(port.flags);
    }
    if ((port.flags & AQ_PORT_MULTI) != 0 &&
        (std::string_view(kind) != "input" || port.type != AQ_PORT_SCENE)) {
      return std::string(kind) + " '" + name +
             "' is AQ_PORT_MULTI: only scene inputs may take several links";
    }
    if ((port.flags & AQ_PORT_8BIT_ENOUGH) != 0 &&
        (std::string_view(kind) != "input" || port.type != AQ_PORT_IMAGE)) {
      return std::string(kind) + " '" + name +
             "' is AQ_PORT_8BIT_ENOUGH: only image inputs may say how they read their image";
    }
    if ((port.flags & AQ_PORT_HDR8) != 0 && port.type != AQ_PORT_IMAGE) {
      return std::string(kind) + " '" + name +
             "' is AQ_PORT_HDR8: only image ports can hold an encoded 8-bit image";
    }
    if ((port.flags & AQ_PORT_BLOCKS) != 0 && (port.flags & AQ_PORT_HDR8) == 0) {
      return std::string(kind) + " '" + name +
             "' is AQ_PORT_BLOCKS without AQ_PORT_HDR8: 2 x 2 blocks hold encoded 8-bit pixels, "
             "so a port that takes them must handle AQ_FORMAT_RGBA8_HDR too";
    }
    if ((port.flags & AQ_PORT_DEFER_AXIS) != 0 && (port.flags & AQ_PORT_BLOCKS) == 0) {
      return std::string(kind) + " '" + name +
             "' is AQ_PORT_DEFER_AXIS without AQ_PORT_BLOCKS: a 1D pass is handed over only "
             "on links stored in 2 x 2 blocks, so the port must take them";
    }
    if (!seen.insert(name).second) {
      return std::string(kind) + " '" + name + "' is declared twice";
    }
    PortInfo info;
    info.name = name;
    info.type = static_cast<aq_port_type>(port.type);
    info.optional = (port.flags & AQ_PORT_OPTIONAL) != 0;
    info.multi = (port.flags & AQ_PORT_MULTI) != 0;
    info.eight_bit_enough = (port.flags & AQ_PORT_8BIT_ENOUGH) != 0;
    info.hdr8 = (port.flags & AQ_PORT_HDR8) != 0;
    info.blocks = (port.flags & AQ_PORT_BLOCKS) != 0;
    info.defer_axis = (port.flags & AQ_PORT_DEFER_AXIS) != 0;
    info.description = text_or_empty(port.description);
    out->push_back(std::move(info));
  }
  return "";
}

// Checks that `value` lies in the parameter's range; returns the reason when it does not.
std::string check_in_range(const ParamInfo& param, double value, const char* what) {
  if (!std::isfinite(value)) return std::string(what) + " is not a finite number";
  if (value < param.min_value || value > param.max_value) {
    return std::string(what) + " " + format_number(value) + " is outside [" +
           format_number(param.min_value) + ", " + format_number(param.max_value) + "]";
  }
  return "";
}

std::string check_param(const aq_param_desc& desc, ParamInfo* info) {
  info->type = static_cast<aq_param_type>(desc.type);
  for (int i = 0; i < 3; ++i) info->default_value[i] = desc.default_value[i];
  info->min_value = desc.min_value;
  info->max_value = desc.max_value;
  info->step = desc.step;
  info->default_string = text_or_empty(desc.default_string);
  info->ui_hint = text_or_empty(desc.ui_hint);
  info->description = text_or_empty(desc.description);

  const bool ranged = desc.type == AQ_PARAM_FLOAT || desc.type == AQ_PARAM_INT ||
                      desc.type == AQ_PARAM_COLOR || desc.type == AQ_PARAM_VEC3;
  if (ranged) {
    if (!std::isfinite(desc.min_value) || !std::isfinite(desc.max_value) ||
        desc.min_value > desc.max_value) {
      return "range [" + format_number(desc.min_value) + ", " + format_number(desc.max_value) +
             "] is not a finite interval with min <= max";
    }
  }
  switch (desc.type) {
    case AQ_PARAM_FLOAT:
      return check_in_range(*info, desc.default_value[0], "default");
    case AQ_PARAM_INT: {
      if (std::string why = check_in_range(*info, desc.default_value[0], "default"); !why.empty()) {
        return why;
      }
      if (std::floor(desc.default_value[0]) != desc.default_value[0]) {
        return "default " + format_number(desc.default_value[0]) + " of an int is not integral";
      }
      return "";
    }
    case AQ_PARAM_BOOL:
      if (desc.default_value[0] != 0.0 && desc.default_value[0] != 1.0) {
        return "default " + format_number(desc.default_value[0]) + " of a bool is not 0 or 1";
      }
      return "";
    case AQ_PARAM_ENUM: {
      if (desc.enum_values == nullptr || desc.enum_values[0] == '\0') {
        return "an enum needs enum_values such as \"gaussian|strided\"";
      }
      info->enum_values = split_enum_values(desc.enum_values);
      std::set<std::string> seen;
      for (const std::string& name : info->enum_values) {
        if (name.empty())
          return "enum_values \"" + std::string(desc.enum_values) + "\" holds an empty name";
        if (!seen.insert(name).second) {
          return "enum value '" + name + "' is listed twice";
        }
      }
      const double index = desc.default_value[0];
      if (!(index >= 0) || std::floor(index) != index ||
          index >= static_cast<double>(info->enum_values.size())) {
        return "default index " + format_number(index) + " is not one of 0.." +
               std::to_string(info->enum_values.size() - 1);
      }
      return "";
    }
    case AQ_PARAM_STRING:
    case AQ_PARAM_PATH:
      return "";
    case AQ_PARAM_COLOR:
    case AQ_PARAM_VEC3: {
      static const char* kComponent[3] = {"default x", "default y", "default z"};
      for (int i = 0; i < 3; ++i) {
        if (std::string why = check_in_range(*info, desc.default_value[i], kComponent[i]);
            !why.empty()) {
          return why;
        }
      }
      return "";
    }
    default:
      return "unknown parameter type " + std::to_string(desc.type) +
             " (expected one of AQ_PARAM_FLOAT..AQ_PARAM_VEC3)";
  }
}

std::string read_params(const aq_param_desc* params, uint32_t count, std::vector<ParamInfo>* out) {
  if (count > 0 && params == nullptr) {
    return "param count is " + std::to_string(count) + " but the array is NULL";
  }
  std::set<std::string> seen;
  for (uint32_t i = 0; i < count; ++i) {
    const aq_param_desc& desc = params[i];
    if (desc.name == nullptr) return "parameter " + std::to_string(i) + " has no name";
    ParamInfo info;
    info.name = desc.name;
    if (!is_type_name(info.name)) {
      return "parameter " + std::to_string(i) + " is named '" + info.name +
             "': parameter names may hold only a-z, 0-9 and '_'";
    }
    if (!seen.insert(info.name).second) {
      return "parameter '" + info.name + "' is declared twice";
    }
    if (!known_param_type(desc.type)) {
      return "parameter '" + info.name + "' has unknown type " + std::to_string(desc.type) +
             " (expected one of AQ_PARAM_FLOAT..AQ_PARAM_VEC3)";
    }
    if (std::string why = check_param(desc, &info); !why.empty()) {
      return "parameter '" + info.name + "' (" + param_type_name(info.type) + "): " + why;
    }
    out->push_back(std::move(info));
  }
  return "";
}

template <typename Info>
const Info* find_named(const std::vector<Info>& items, const std::string& name) {
  for (const Info& item : items) {
    if (item.name == name) return &item;
  }
  return nullptr;
}

template <typename Info>
int index_of_named(const std::vector<Info>& items, const std::string& name) {
  for (size_t i = 0; i < items.size(); ++i) {
    if (items[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace

const PortInfo* NodeType::input(const std::string& port) const {
  return find_named(inputs, port);
}
const PortInfo* NodeType::output(const std::string& port) const {
  return find_named(outputs, port);
}
const ParamInfo* NodeType::param(const std::string& param_name) const {
  return find_named(params, param_name);
}
int NodeType::input_index(const std::string& port) const {
  return index_of_named(inputs, port);
}
int NodeType::output_index(const std::string& port) const {
  return index_of_named(outputs, port);
}
int NodeType::param_index(const std::string& param_name) const {
  return index_of_named(params, param_name);
}

NodeType node_type_from_desc(const aq_node_desc& desc, const std::string& plugin_file,
                             std::string* why) {
  const std::string type_label = desc.type_name != nullptr
                                     ? "node type '" + std::string(desc.type_name) + "'"
                                     : std::string("a node type");
  auto refuse = [&](const std::string& reason) {
    if (why != nullptr) *why = type_label + " in " + plugin_file + ": " + reason;
    return NodeType{};
  };

  // ABI 1 grows at the end: a description from before `pointwise` was appended still loads.
  constexpr size_t kFirstSize = offsetof(aq_node_desc, pointwise);
  if (desc.struct_size < kFirstSize) {
    return refuse("struct_size " + std::to_string(desc.struct_size) + " is smaller than " +
                  std::to_string(kFirstSize) + " (the plugin was built against another plugin.h)");
  }
  if (desc.type_name == nullptr) return refuse("type_name is NULL");
  NodeType type;
  type.name = desc.type_name;
  if (!is_type_name(type.name)) {
    return refuse("the type name may hold only a-z, 0-9 and '_'");
  }
  const uint32_t known_flags = AQ_NODE_TIME_DEPENDENT | AQ_NODE_POINTWISE | AQ_NODE_EPILOGUE;
  if ((desc.flags & ~known_flags) != 0) {
    return refuse("unknown flags " + std::to_string(desc.flags & ~known_flags));
  }
  if (desc.create == nullptr || desc.destroy == nullptr || desc.process == nullptr) {
    return refuse("create, destroy and process must all be set");
  }
  if (std::string reason = read_ports(desc.inputs, desc.input_count, "input", &type.inputs);
      !reason.empty()) {
    return refuse(reason);
  }
  if (std::string reason = read_ports(desc.outputs, desc.output_count, "output", &type.outputs);
      !reason.empty()) {
    return refuse(reason);
  }
  if (std::string reason = read_params(desc.params, desc.param_count, &type.params);
      !reason.empty()) {
    return refuse(reason);
  }
  if (desc.struct_size >= offsetof(aq_node_desc, pointwise) + sizeof(desc.pointwise) &&
      desc.pointwise != nullptr) {
    const aq_pointwise_desc& pointwise = *desc.pointwise;
    // Input 0 is the image the function maps pixel by pixel; further image inputs (edge's
    // detection source) are bound by the host as samplers the function may read anywhere.
    bool images_in_one_out =
        !type.inputs.empty() && type.outputs.size() == 1 && type.outputs[0].type == AQ_PORT_IMAGE;
    for (const PortInfo& port : type.inputs)
      images_in_one_out = images_in_one_out && port.type == AQ_PORT_IMAGE && !port.multi;
    if ((desc.flags & AQ_NODE_POINTWISE) == 0 || !images_in_one_out) {
      return refuse(
          "a fusable function (pointwise) needs the AQ_NODE_POINTWISE flag, image inputs only "
          "(the first is the one it maps pixel by pixel) and one image output");
    }
    if (pointwise.struct_size < sizeof(aq_pointwise_desc) || pointwise.glsl == nullptr ||
        pointwise.set_uniforms == nullptr) {
      return refuse("its pointwise description needs struct_size, glsl and set_uniforms");
    }
    type.fusable = &pointwise;
  }
  if ((desc.flags & AQ_NODE_EPILOGUE) != 0 &&
      (type.fusable != nullptr || type.outputs.empty() || type.outputs[0].type != AQ_PORT_IMAGE)) {
    return refuse(
        "AQ_NODE_EPILOGUE needs an image as output 0 and a node that is not itself fusable "
        "(a pointwise node is fused by its function instead)");
  }
  type.category = text_or_empty(desc.category);
  type.description = text_or_empty(desc.description);
  type.flags = desc.flags;
  type.plugin_file = plugin_file;
  type.desc = &desc;
  if (why != nullptr) why->clear();
  return type;
}

bool Registry::add(NodeType type, std::string* why) {
  if (type.name.empty()) {
    if (why != nullptr) *why = "a node type without a name cannot be registered";
    return false;
  }
  auto existing = types_.find(type.name);
  if (existing != types_.end()) {
    if (why != nullptr) {
      *why = "node type '" + type.name + "' from " + type.plugin_file + " is already provided by " +
             existing->second.plugin_file + "; remove one of the two plugins from the plugin path";
    }
    return false;
  }
  const std::string name = type.name;
  types_.emplace(name, std::move(type));
  return true;
}

const NodeType* Registry::find(const std::string& name) const {
  auto it = types_.find(name);
  return it != types_.end() ? &it->second : nullptr;
}

std::vector<std::string> Registry::names() const {
  std::vector<std::string> result;
  result.reserve(types_.size());
  for (const auto& [name, type] : types_) result.push_back(name);
  return result;
}

const char* port_type_name(aq_port_type type) {
  switch (type) {
    case AQ_PORT_IMAGE:
      return "image";
    case AQ_PORT_SCENE:
      return "scene";
  }
  return "unknown";
}

const char* param_type_name(aq_param_type type) {
  switch (type) {
    case AQ_PARAM_FLOAT:
      return "float";
    case AQ_PARAM_INT:
      return "int";
    case AQ_PARAM_BOOL:
      return "bool";
    case AQ_PARAM_ENUM:
      return "enum";
    case AQ_PARAM_STRING:
      return "string";
    case AQ_PARAM_PATH:
      return "path";
    case AQ_PARAM_COLOR:
      return "color";
    case AQ_PARAM_VEC3:
      return "vec3";
  }
  return "unknown";
}

}  // namespace aq
