// Compiling the evaluation plan (see plan.h).
#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/plan.h>
#include <aquarelle/core/texture_pool.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <set>

namespace aq {

namespace {

// Depth-first from the output: only what it depends on, inputs before their readers.
Status cull_and_sort(const Graph& graph, const std::string& target,
                     std::vector<std::string>* order) {
  std::map<std::string, int> mark;  // 1 visiting, 2 done
  std::vector<std::string> path;
  std::function<Status(const std::string&)> visit = [&](const std::string& id) -> Status {
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
      if (auto s = visit(source.node); !s.ok()) return s;
    }
    mark[id] = 2;
    path.pop_back();
    order->push_back(id);
    return Ok{};
  };
  return visit(target);
}

// The node linked to a node's first input (the image a pointwise node transforms), if any.
const std::string* first_input_source(const Node& node, const NodeType& type) {
  if (type.inputs.empty()) return nullptr;
  auto link = node.inputs.find(type.inputs[0].name);
  return link == node.inputs.end() ? nullptr : &link->second.node;
}

// Nodes that run inside their reader's pass instead of a pass of their own. Pointwise nodes:
// they give a fusable function, are not the output, and their only reader is another such
// node reading them on its image input. Epilogue producers (`epilogue`, no proxy render): an
// AQ_NODE_EPILOGUE node whose only reader is such a node, reading its output 0; its process()
// then runs in the chain's pass with the chain as the epilogue of its last draw.
std::set<std::string> deferred_nodes(const Graph& graph, const Registry& registry,
                                     const std::vector<std::string>& order,
                                     const std::map<std::string, int>& readers,
                                     const std::string& target, bool epilogue) {
  std::set<std::string> deferred;
  // A fusable node whose extra image inputs are all connected (aq_pointwise_desc).
  auto fusable = [&](const std::string& id) {
    const Node& node = graph.nodes.at(id);
    const NodeType* type = registry.find(node.type);
    if (type == nullptr || type->fusable == nullptr) return false;
    for (size_t i = 1; i < type->inputs.size(); ++i)
      if (node.inputs.count(type->inputs[i].name) == 0) return false;
    return true;
  };
  for (const auto& reader_id : order) {
    if (!fusable(reader_id)) continue;
    const NodeType* reader_type = registry.find(graph.nodes.at(reader_id).type);
    const std::string* source = first_input_source(graph.nodes.at(reader_id), *reader_type);
    if (source == nullptr) continue;
    if (*source == target || readers.at(*source) != 1) continue;
    const NodeType* source_type = registry.find(graph.nodes.at(*source).type);
    const std::string& port = graph.nodes.at(reader_id).inputs.at(reader_type->inputs[0].name).port;
    if (fusable(*source) || (epilogue && source_type != nullptr && source_type->takes_epilogue() &&
                             port == source_type->outputs[0].name))
      deferred.insert(*source);
  }
  return deferred;
}

// One input that reads a node's output port: the reader, its type and the input's index in it
// (-1 when the type has no such input).
struct ReaderInput {
  std::string reader;
  const NodeType* type = nullptr;
  int index = -1;
};

std::vector<ReaderInput> readers_of(const Graph& graph, const Registry& registry,
                                    const std::vector<std::string>& order, const std::string& id,
                                    const std::string& port) {
  std::vector<ReaderInput> readers;
  for (const auto& reader_id : order) {
    const Node& reader = graph.nodes.at(reader_id);
    const NodeType* reader_type = registry.find(reader.type);
    for (const auto& [input, source] : reader.inputs) {
      if (source.node != id || source.port != port) continue;
      readers.push_back({reader_id, reader_type, reader_type->input_index(input)});
    }
  }
  return readers;
}

// The format each image output of `id` is stored in when its readers need less than the
// writer's own format (bandwidth by need), 0 where the writer's choice stands:
// - AQ_FORMAT_RGBA8_HDR when the writer and every reader handle it (AQ_PORT_HDR8) and the graph
//   works in half precision (float asks for accuracy over speed);
// - AQ_FORMAT_RGBA8 when every reader reads through an AQ_PORT_8BIT_ENOUGH input.
// An output nobody reads and the requested output keep their format. Empty when none changes.
// `epilogue_writer`: the output 0 of the producer whose last draw applies the chain ending at
// `id` (epilogue fusion), whose promises (AQ_PORT_HDR8, AQ_PORT_BLOCKS) are then the writer's.
std::vector<uint32_t> stored_formats(const Graph& graph, const Registry& registry,
                                     const std::vector<std::string>& order, const std::string& id,
                                     const NodeType& type, const PortRef& target, bool hdr8,
                                     bool blocks, const PortInfo* epilogue_writer) {
  std::vector<uint32_t> formats(type.outputs.size(), 0);
  bool any = false;
  const bool half = graph.settings.precision != "float";
  for (size_t o = 0; o < type.outputs.size(); ++o) {
    if (type.outputs[o].type != AQ_PORT_IMAGE) continue;
    const std::string& port = type.outputs[o].name;
    if (target.node == id && target.port == port) continue;
    const std::vector<ReaderInput> readers = readers_of(graph, registry, order, id, port);
    if (readers.empty()) continue;
    bool all_eight_bit = true;
    bool all_hdr8 = true;
    bool all_blocks = true;
    for (const ReaderInput& r : readers) {
      const PortInfo* input = r.index >= 0 ? &r.type->inputs[r.index] : nullptr;
      all_eight_bit = all_eight_bit && input != nullptr && input->eight_bit_enough;
      all_hdr8 = all_hdr8 && input != nullptr && input->hdr8;
      all_blocks = all_blocks && input != nullptr && input->blocks;
    }
    const PortInfo& writer = epilogue_writer != nullptr ? *epilogue_writer : type.outputs[o];
    if (all_hdr8 && hdr8 && half && writer.hdr8) {
      formats[o] =
          all_blocks && blocks && writer.blocks ? AQ_FORMAT_RGBA8_HDR_BLOCKS : AQ_FORMAT_RGBA8_HDR;
    } else if (all_eight_bit) {
      formats[o] = AQ_FORMAT_RGBA8;
    }
    any = any || formats[o] != 0;
  }
  return any ? formats : std::vector<uint32_t>{};
}

// Which outputs of `id`, stored as `formats`, may leave their last 1D pass to their one reader
// (PlannedNode::axis_deferrable). Empty when none may.
std::vector<bool> axis_deferrable(const Graph& graph, const Registry& registry,
                                  const std::vector<std::string>& order,
                                  const std::set<std::string>& deferred, const std::string& id,
                                  const NodeType& type, const std::vector<uint32_t>& formats) {
  std::vector<bool> deferrable(type.outputs.size(), false);
  bool any = false;
  for (size_t o = 0; o < formats.size() && o < type.outputs.size(); ++o) {
    if (formats[o] != AQ_FORMAT_RGBA8_HDR_BLOCKS || !type.outputs[o].defer_axis) continue;
    const std::vector<ReaderInput> readers =
        readers_of(graph, registry, order, id, type.outputs[o].name);
    deferrable[o] = readers.size() == 1 && readers[0].index >= 0 &&
                    readers[0].type->inputs[readers[0].index].defer_axis &&
                    deferred.count(readers[0].reader) == 0;
    any = any || deferrable[o];
  }
  return any ? deferrable : std::vector<bool>{};
}

}  // namespace

const PlannedNode* Plan::find(const std::string& id) const {
  for (const auto& node : nodes)
    if (node.id == id) return &node;
  return nullptr;
}

const PlannedPass* Plan::pass_of(const std::string& id) const {
  for (const auto& pass : passes)
    if (std::find(pass.chain.begin(), pass.chain.end(), id) != pass.chain.end()) return &pass;
  return nullptr;
}

namespace {

// The port to render: the requested one or the graph's output, present and within the node
// budget (graphs never validated, built in Python or the editor, meet the same bound).
Result<PortRef> render_target(const Graph& graph, const std::optional<PortRef>& requested) {
  std::optional<PortRef> target = requested ? requested : graph.output;
  if (!target)
    return make_error(
        "the graph has no `output`: name the port to render, e.g. "
        "\"output\": \"tint.image\"");
  if (graph.nodes.find(target->node) == graph.nodes.end()) {
    return make_error("output '" + target->str() + "' names node '" + target->node +
                      "', which is not in the graph");
  }
  if (std::string why = node_count_problem(graph, *target); !why.empty()) return make_error(why);
  return *target;
}

// How many links (and the requested output) read each node of `order`.
std::map<std::string, int> count_readers(const Graph& graph, const std::vector<std::string>& order,
                                         const std::string& target) {
  std::map<std::string, int> readers;
  for (const auto& id : order) readers[id] += 0;
  for (const auto& id : order) {
    for (const auto& [port, source] : graph.nodes.at(id).inputs) ++readers[source.node];
  }
  readers[target] += 1;
  return readers;
}

}  // namespace

Result<Plan> compile_plan(const Graph& graph, const Registry& registry, const PlanOptions& options,
                          const std::optional<PortRef>& requested) {
  Plan plan;
  auto resolved = render_target(graph, requested);
  if (!resolved.ok()) return resolved.error();
  const std::optional<PortRef> target = resolved.value();
  plan.output = *target;
  plan.working = working_size(graph.settings);
  plan.output_size = PixelSize{graph.settings.width, graph.settings.height};
  plan.format = graph.settings.precision == "float" ? AQ_FORMAT_RGBA32F : AQ_FORMAT_RGBA16F;

  std::vector<std::string> order;
  if (auto s = cull_and_sort(graph, target->node, &order); !s.ok()) return s.error();
  for (const auto& id : order) {
    const Node& node = graph.nodes.at(id);
    if (registry.find(node.type) == nullptr) {
      return make_error("node '" + id + "': unknown node type '" + node.type +
                        "' (run `aquarelle nodes` to list the installed types)");
    }
  }

  std::map<std::string, int> readers = count_readers(graph, order, target->node);
  const bool proxy = plan.working.width != plan.output_size.width ||
                     plan.working.height != plan.output_size.height;
  // A proxy render resamples the output's pointwise tail instead (the producer would have to
  // write at the graph's size).
  const std::set<std::string> deferred =
      options.fuse_pointwise ? deferred_nodes(graph, registry, order, readers, target->node,
                                              options.epilogue_fusion && !proxy)
                             : std::set<std::string>{};

  std::map<std::string, bool> varies;
  std::map<std::string, std::vector<std::string>> chain_of;  // deferred stages ending at a node
  for (const auto& id : order) {
    const Node& node = graph.nodes.at(id);
    const NodeType* type = registry.find(node.type);
    PlannedNode planned;
    planned.id = id;
    planned.type = type;
    planned.readers = readers[id];
    planned.varies = type->time_dependent();
    for (const auto& [port, source] : node.inputs)
      planned.varies = planned.varies || varies[source.node];
    varies[id] = planned.varies;
    planned.deferred = deferred.count(id) != 0;
    planned.producer = planned.deferred && type->fusable == nullptr;

    // The chain of deferred nodes feeding this one through its first input.
    std::vector<std::string> chain;
    if (type->fusable != nullptr) {
      if (const std::string* source = first_input_source(node, *type)) {
        if (auto found = chain_of.find(*source); found != chain_of.end()) {
          chain = std::move(found->second);
          chain_of.erase(found);
        }
      }
    }
    chain.push_back(id);
    // A fused pass is one shader holding every stage: its size, and the driver's compile
    // time (worse than linear: a 1,000-node chain took over a minute), grow with the chain.
    // A long chain is cut into passes of at most kMaxFusedStages stages instead.
    if (planned.deferred && !planned.producer && chain.size() >= kMaxFusedStages) {
      planned.deferred = false;
    }
    for (const PortInfo& output : type->outputs) {
      planned.outputs_read.push_back((id == target->node && output.name == target->port) ||
                                     !readers_of(graph, registry, order, id, output.name).empty());
    }
    if (options.formats_by_need && !planned.deferred) {
      const PlannedNode* head = chain.empty() ? nullptr : plan.find(chain.front());
      const PortInfo* epilogue_writer =
          head != nullptr && head->producer && !head->type->outputs.empty()
              ? &head->type->outputs[0]
              : nullptr;
      const bool blocks = options.blocks && (epilogue_writer == nullptr || options.epilogue_blocks);
      planned.stored_formats = stored_formats(graph, registry, order, id, *type, *target,
                                              options.hdr8, blocks, epilogue_writer);
    }
    plan.nodes.push_back(planned);
    if (planned.deferred) {
      chain_of[id] = std::move(chain);
      continue;
    }
    PlannedPass pass;
    pass.node = id;
    pass.chain = std::move(chain);
    pass.size = plan.working;
    pass.format = plan.format;
    pass.resamples = options.fuse_pointwise && type->fusable != nullptr && id == target->node &&
                     proxy && first_input_source(node, *type) != nullptr;
    if (pass.resamples) pass.size = plan.output_size;
    pass.fused = pass.chain.size() > 1 || pass.resamples;
    const PlannedNode* head = plan.find(pass.chain.front());
    pass.epilogue = head != nullptr && head->producer;
    // 8-bit HDR and 2 x 2 blocks are promises of the pass's writer: the host's fused pass
    // encodes pixels; an epilogue producer's output 0 made them (stored_formats).
    if (options.defer_axis)
      plan.nodes.back().axis_deferrable = axis_deferrable(graph, registry, order, deferred, id,
                                                          *type, plan.nodes.back().stored_formats);
    pass.reads_per_pixel = pass.fused && !pass.epilogue ? 1 : -1;
    pass.intermediates_saved = static_cast<int>(pass.chain.size()) - 1;
    pass.cached = !planned.varies && options.retain_static_outputs;
    plan.passes.push_back(std::move(pass));
  }
  const PlannedPass* last = plan.pass_of(target->node);
  plan.upscale = proxy && !(last != nullptr && last->resamples);
  return plan;
}

std::string format_plan(const Plan& plan) {
  std::string text;
  char line[256];
  std::snprintf(line, sizeof(line),
                "plan for %s: working size %dx%d, output %dx%d, %s; %zu node(s) in %zu pass(es)\n",
                plan.output.str().c_str(), plan.working.width, plan.working.height,
                plan.output_size.width, plan.output_size.height, format_name(plan.format),
                plan.nodes.size(), plan.passes.size() + (plan.upscale ? 1 : 0));
  text += line;
  std::snprintf(line, sizeof(line), "%-4s %-16s %-14s %-11s %-8s %-7s %-6s %s\n", "pass", "node",
                "type", "size", "format", "reads", "static", "computes");
  text += line;
  int index = 0;
  for (const auto& pass : plan.passes) {
    const PlannedNode* node = plan.find(pass.node);
    std::string chain;
    for (const auto& id : pass.chain) chain += (chain.empty() ? "" : " -> ") + id;
    if (pass.epilogue) {
      chain = "epilogue: " + chain;
    } else if (pass.fused) {
      chain = "fused: " + chain;
    }
    if (pass.resamples) chain += " (inside the upscale)";
    for (const uint32_t format :
         {AQ_FORMAT_RGBA8, AQ_FORMAT_RGBA8_HDR, AQ_FORMAT_RGBA8_HDR_BLOCKS}) {
      std::string narrow;
      for (size_t o = 0; o < node->stored_formats.size(); ++o)
        if (node->stored_formats[o] == format)
          narrow += (narrow.empty() ? "" : ", ") + node->type->outputs[o].name;
      if (!narrow.empty()) chain += std::string(" [") + format_name(format) + ": " + narrow + "]";
    }
    std::string handed;
    for (size_t o = 0; o < node->axis_deferrable.size(); ++o)
      if (node->axis_deferrable[o])
        handed += (handed.empty() ? "" : ", ") + node->type->outputs[o].name;
    if (!handed.empty()) chain += " [last 1D pass to its reader: " + handed + "]";
    char size[32];
    std::snprintf(size, sizeof(size), "%dx%d", pass.size.width, pass.size.height);
    const std::string reads =
        pass.reads_per_pixel < 0 ? std::string("node") : std::to_string(pass.reads_per_pixel);
    std::snprintf(line, sizeof(line), "%-4d %-16s %-14s %-11s %-8s %-7s %-6s %s\n", ++index,
                  pass.node.c_str(), node->type->name.c_str(), size, format_name(pass.format),
                  reads.c_str(), pass.cached ? "yes" : "no", chain.c_str());
    text += line;
  }
  if (plan.upscale) {
    std::snprintf(line, sizeof(line), "%-4d %-16s %-14s %dx%d bilinear upscale of %s\n", ++index,
                  "(host)", "resample", plan.output_size.width, plan.output_size.height,
                  plan.output.str().c_str());
    text += line;
  }
  text +=
      "reads: image reads per output pixel of a host-fused pass; 'node': the node's own "
      "process() decides (sizes of shadow maps and caustic textures too)\n"
      "epilogue: the first node's process() runs with the pointwise nodes after it applied "
      "in its last draw (AQ_NODE_EPILOGUE)\n"
      "[RGBA8: port]: outputs stored in 8 bits because every reader reads them through an "
      "input content with 8 bits; [RGBA8 HDR: port]: linear HDR colour encoded in 8 bits "
      "(sqrt(c / (1 + c))) because its writer and every reader handle that (bandwidth by "
      "need); [RGBA8 HDR 2x2: port]: the same in 2 x 2 blocks of packed pixels, between "
      "nodes that work on whole blocks (a morphology chain, the wobble to the blur); [last 1D "
      "pass to its reader: port]: a separable filter leaves its last 1D pass undone and its "
      "reader runs it in one pass with its own first one along the same axis "
      "(AQ_PORT_DEFER_AXIS)\n";
  return text;
}

}  // namespace aq
