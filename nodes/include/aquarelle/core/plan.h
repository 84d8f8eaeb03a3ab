// The evaluation plan: what one evaluation of a graph will do, decided before anything runs, as
// Filament's FrameGraph compiles its passes before executing them.
//
//   declare   the graph and the requested output
//   compile   cull to the nodes the output depends on, sort them (inputs first), count the
//             readers of each node, mark what is static (nothing upstream depends on time),
//             choose which pointwise nodes run inside their reader's pass (fusion), size and
//             format every pass, and whether the output is resampled to the graph's size
//   execute   Evaluator::evaluate walks plan.nodes in order (evaluator.cpp)
//
// The plan is a plain value: tests inspect it and `aquarelle render --plan` prints it.
#pragma once

#include <aquarelle/core/graph.h>
#include <aquarelle/core/quality.h>
#include <aquarelle/core/registry.h>
#include <aquarelle/core/result.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace aq {

struct PlannedNode {
  std::string id;
  const NodeType* type = nullptr;
  int readers = 0;        // links that read this node's outputs (+1 for the requested output)
  bool varies = false;    // it or something upstream is time-dependent; else cached across frames
  bool deferred = false;  // runs inside its reader's pass (pointwise fusion), not a pass of its own
  // Deferred as the producer of its reader's pointwise chain (AQ_NODE_EPILOGUE): its process()
  // runs in the chain's pass, the chain applied in its last draw.
  bool producer = false;
  // Per output port (type order): the format the host stores it in instead of the one its
  // plugin asks for (bandwidth by need), 0 where the plugin's choice stands: AQ_FORMAT_RGBA8
  // when every reader reads it through an AQ_PORT_8BIT_ENOUGH input, AQ_FORMAT_RGBA8_HDR when
  // the writer and every reader say AQ_PORT_HDR8 (half precision only), AQ_FORMAT_RGBA8_HDR_BLOCKS
  // when they also say AQ_PORT_BLOCKS (a morphology chain). Never the requested output. Empty
  // when no output changes.
  std::vector<uint32_t> stored_formats;
  // Per output port (type order): true where the writer may leave its last 1D pass to the one
  // node that reads it (AQ_PORT_DEFER_AXIS on both ends of a link stored in blocks, not the
  // requested output): neighbourhood fusion, the two same-axis passes at the link run as one.
  // Empty when no output may.
  std::vector<bool> axis_deferrable;
  // Per output port (type order): a link of the plan reads it, or it is the requested output.
  // An unread output may be left unwritten (aq_host::output_read).
  std::vector<bool> outputs_read;
};

// One pass of the frame: a node's process(), or one fused shader that computes a chain of
// pointwise nodes (the last of them owns the pass).
struct PlannedPass {
  std::string node;                // the node that runs it (owns its output)
  std::vector<std::string> chain;  // fused nodes, in order, ending with `node`; {node} alone
  PixelSize size;                  // the pass's output size
  uint32_t format = 0;             // the working format its image outputs use (aq_image_format)
  bool fused = false;              // a host-generated shader runs the chain
  bool resamples = false;          // reads the working size, writes the graph's size
  bool cached = false;             // static: computed once, reused while its key holds
  bool epilogue = false;           // chain.front() is an epilogue producer (PlannedNode::producer)
  // Image reads per output pixel when the host knows them (fused passes: one texel or one
  // bilinear lookup of the chain's input), -1 for a plugin's own process().
  int reads_per_pixel = -1;
  // Full-size intermediates that fusion saved (one write and one read each).
  int intermediates_saved = 0;
};

struct Plan {
  PortRef output;
  PixelSize working;               // the size nodes render at (quality preset's render scale)
  PixelSize output_size;           // the graph's size
  uint32_t format = 0;             // working format
  std::vector<PlannedNode> nodes;  // execution order: inputs before readers
  std::vector<PlannedPass> passes;
  // The output (at the working size) is resampled to the graph's size by one more pass unless
  // the output's pointwise tail already does it (its pass `resamples`).
  bool upscale = false;

  const PlannedNode* find(const std::string& id) const;
  const PlannedPass* pass_of(const std::string& id) const;  // the pass that computes node id
};

// The most stages one fused pass holds (plan.cpp: longer chains are cut into several passes).
inline constexpr size_t kMaxFusedStages = 32;

struct PlanOptions {
  bool fuse_pointwise = true;
  // With fuse_pointwise: a pointwise chain runs in the last draw of an AQ_NODE_EPILOGUE node it
  // alone reads (not in proxy renders, whose tail runs in the upscale).
  bool epilogue_fusion = true;
  bool retain_static_outputs = true;  // static nodes' results kept across frames
  // Store outputs in the narrower format their readers need (PlannedNode::stored_formats).
  bool formats_by_need = true;
  // ... including AQ_FORMAT_RGBA8_HDR (with formats_by_need).
  bool hdr8 = true;
  // ... and AQ_FORMAT_RGBA8_HDR_BLOCKS between AQ_PORT_BLOCKS ports (with hdr8).
  bool blocks = true;
  // ... also where an epilogue producer writes a fused chain's result (with blocks).
  bool epilogue_blocks = true;
  // ... and a separable filter's last 1D pass handed to its reader (PlannedNode::axis_deferrable).
  bool defer_axis = true;
};

// Compiles the plan; errors name the node (cycle, missing node, unknown type, bad output).
Result<Plan> compile_plan(const Graph& graph, const Registry& registry, const PlanOptions& options,
                          const std::optional<PortRef>& output = std::nullopt);

// The plan as a table, one line per pass (what `aquarelle render --plan` prints).
std::string format_plan(const Plan& plan);

}  // namespace aq
