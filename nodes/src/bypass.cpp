// Bypass as a graph rewrite before planning. See bypass.h.
#include <aquarelle/core/bypass.h>

#include <algorithm>
#include <optional>

namespace aq {
namespace {

// Deeper than any chain of bypassed nodes without a cycle (validation refuses cycles).
constexpr int kMaxChain = 256;

// The source that the output `ref` of a bypassed node passes through, or nullopt with `why`.
std::optional<PortRef> pass_through(const Graph& graph, const Registry& registry,
                                    const PortRef& ref, std::string* why) {
  auto node = graph.nodes.find(ref.node);
  if (node == graph.nodes.end() || !node->second.bypass) return ref;
  const NodeType* type = registry.find(node->second.type);
  const PortInfo* port = type != nullptr ? type->output(ref.port) : nullptr;
  if (port == nullptr) return ref;  // validation reports the unknown type or port
  for (const auto& input : type->inputs) {
    if (input.type != port->type) continue;
    auto linked = node->second.inputs.find(input.name);
    if (linked == node->second.inputs.end()) {
      *why = "node '" + ref.node + "' (" + type->name + ") is bypassed but its input '" +
             input.name + "' is not linked, so there is nothing to pass through: link it, or " +
             "enable the node (remove \"bypass\": true)";
      return std::nullopt;
    }
    return linked->second;
  }
  *why = "node '" + ref.node + "' (" + type->name + ") is bypassed but has no " +
         (port->type == AQ_PORT_SCENE ? "scene" : "image") + " input to pass its output '" +
         ref.port + "' through: enable it (remove \"bypass\": true) or delete it";
  return std::nullopt;
}

std::optional<PortRef> resolve(const Graph& graph, const Registry& registry, PortRef ref,
                               std::string* why) {
  for (int depth = 0; depth < kMaxChain; ++depth) {
    auto next = pass_through(graph, registry, ref, why);
    if (!next) return std::nullopt;
    if (*next == ref) return ref;
    ref = *next;
  }
  *why = "node '" + ref.node + "': the chain of bypassed nodes before it does not end";
  return std::nullopt;
}

}  // namespace

bool has_bypassed_nodes(const Graph& graph) {
  return std::any_of(graph.nodes.begin(), graph.nodes.end(),
                     [](const auto& entry) { return entry.second.bypass; });
}

Result<PortRef> bypass_source(const Graph& graph, const Registry& registry, const PortRef& ref) {
  std::string why;
  auto resolved = resolve(graph, registry, ref, &why);
  if (!resolved) return make_error(why);
  return *resolved;
}

Result<Graph> apply_bypass(const Graph& graph, const Registry& registry) {
  Graph out = graph;
  if (!has_bypassed_nodes(graph)) return out;
  std::string why;
  for (auto& [id, node] : out.nodes) {
    if (node.bypass) continue;  // read by nobody once its readers are redirected
    for (auto& [port, source] : node.inputs) {
      auto resolved = resolve(graph, registry, source, &why);
      if (!resolved) return make_error(why);
      source = *resolved;
    }
  }
  if (out.output) {
    auto resolved = resolve(graph, registry, *out.output, &why);
    if (!resolved) return make_error(why);
    out.output = *resolved;
  }
  // A bypassed node's own links are left; nothing reads the node now, so the plan culls it.
  return out;
}

Result<BypassedGraph> bypassed_graph(const Graph& graph, const Registry& registry,
                                     const std::optional<PortRef>& requested) {
  BypassedGraph out;
  out.output = requested;
  if (!has_bypassed_nodes(graph)) return out;
  auto rewritten = apply_bypass(graph, registry);
  if (!rewritten.ok()) return rewritten.error();
  out.rewritten = std::move(*rewritten);
  if (requested) {
    auto source = bypass_source(graph, registry, *requested);
    if (!source.ok()) return source.error();
    out.output = *source;
  }
  return out;
}

}  // namespace aq
