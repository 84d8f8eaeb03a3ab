// The node types the host knows: copied out of plugin descriptions (or built in) into C++
// values, so the validator, the editor's panels and `aquarelle nodes` read one model.
#pragma once

#include <aquarelle/plugin.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace aq {

struct PortInfo {
  std::string name;
  aq_port_type type = AQ_PORT_IMAGE;
  bool optional = false;
  std::string description;
  bool multi = false;  // takes any number of links (AQ_PORT_MULTI)
  // An image input content with 8 bits a channel (AQ_PORT_8BIT_ENOUGH).
  bool eight_bit_enough = false;
  // An image port that handles AQ_FORMAT_RGBA8_HDR (AQ_PORT_HDR8).
  bool hdr8 = false;
  // ... and AQ_FORMAT_RGBA8_HDR_BLOCKS too (AQ_PORT_BLOCKS).
  bool blocks = false;
  // ... and may leave its last 1D pass to its reader, or run its writer's (AQ_PORT_DEFER_AXIS).
  bool defer_axis = false;
};

struct ParamInfo {
  std::string name;
  aq_param_type type = AQ_PARAM_FLOAT;
  double default_value[3] = {0, 0, 0};
  double min_value = 0;
  double max_value = 0;
  double step = 0;
  std::string default_string;
  std::vector<std::string> enum_values;
  std::string ui_hint;
  std::string description;
};

struct NodeType {
  std::string name;
  std::string category;
  std::string description;
  uint32_t flags = 0;
  std::vector<PortInfo> inputs;
  std::vector<PortInfo> outputs;
  std::vector<ParamInfo> params;
  std::string plugin_file;             // "(built in)" for host node types
  const aq_node_desc* desc = nullptr;  // null for host-built-in types
  // The per-pixel function the evaluator may fuse (pointwise nodes that give one), else null.
  const aq_pointwise_desc* fusable = nullptr;

  bool time_dependent() const { return (flags & AQ_NODE_TIME_DEPENDENT) != 0; }
  bool pointwise() const { return (flags & AQ_NODE_POINTWISE) != 0; }
  bool takes_epilogue() const { return (flags & AQ_NODE_EPILOGUE) != 0; }
  bool has_multi_input() const {
    for (const PortInfo& port : inputs) {
      if (port.multi) return true;
    }
    return false;
  }
  const PortInfo* input(const std::string& port) const;
  const PortInfo* output(const std::string& port) const;
  const ParamInfo* param(const std::string& name) const;
  int input_index(const std::string& port) const;
  int output_index(const std::string& port) const;
  int param_index(const std::string& name) const;
};

// Builds a NodeType from a plugin's description; returns an empty name and sets `why` when the
// description is invalid (missing names, bad types, duplicate ports, default out of range...).
NodeType node_type_from_desc(const aq_node_desc& desc, const std::string& plugin_file,
                             std::string* why);

class Registry {
 public:
  // Adds a type; refuses (returns false, sets why) a duplicate name.
  bool add(NodeType type, std::string* why);
  const NodeType* find(const std::string& name) const;
  std::vector<std::string> names() const;  // sorted
  const std::map<std::string, NodeType>& types() const { return types_; }

 private:
  std::map<std::string, NodeType> types_;
};

const char* port_type_name(aq_port_type type);
const char* param_type_name(aq_param_type type);

}  // namespace aq
