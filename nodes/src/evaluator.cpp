// Evaluator: executes an evaluation plan (plan.h: cull, sort, readers, fusion, sizes) one node
// at a time through the steps of frame_run.h: the node's key and inputs (node_call.h), fusion
// (fused_chain.h), run or reuse, timing, and the release of what no reader needs. The host
// services a plugin calls live in host_services.cpp; pointwise fusion's shader in
// pointwise_fusion.cpp.
#include <aquarelle/core/evaluator.h>

#include <aquarelle/core/bypass.h>
#include <aquarelle/core/plan.h>

#include <cstdlib>
#include <string>

#include "frame_run.h"
#include "host_services.h"
#include "pointwise_fusion.h"
#include "shader_cache.h"

namespace aq {

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
  // Drops the state of nodes that left the graph or changed type.
  void drop_stale_states(const Graph& graph) {
    for (auto it = states.begin(); it != states.end();) {
      auto node = graph.nodes.find(it->first);
      if (node == graph.nodes.end() || it->second.type == nullptr ||
          node->second.type != it->second.type->name) {
        destroy_state(it->second);
        it = states.erase(it);
      } else {
        ++it;
      }
    }
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
  plan_options.epilogue_blocks =
      plan_options.blocks && enabled_in_environment("AQUARELLE_EPILOGUE_BLOCKS");
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
  if (!context_.activate()) return make_error("the OpenGL context cannot be made current");
  impl_->host.make_current();
  impl_->drop_stale_states(graph);
  auto plan = compile(graph, registry_, options, bypassed->output);  // bypass already applied
  if (!plan.ok()) return plan.error();

  FrameRun run({impl_->host, impl_->fuser, impl_->states, timings_, run_counts_}, graph, *plan,
               options, context_.generation());
  for (const PlannedNode& planned : plan->nodes) {
    NodeState& state = run.state_of(planned);
    auto call = run.prepare(planned);  // the node's key; its inputs
    if (!call.ok()) return call.error();
    auto chain = run.fuse(planned, state, *call);  // join or start a pointwise chain
    if (!chain.ok()) return chain.error();
    const Status ran = planned.deferred             ? run.defer(planned, state, *call, *chain)
                       : run.reusable(state, *call) ? run.reuse(planned)
                       : *chain                     ? run.run_chain(planned, state, *call, **chain)
                                                    : run.run_node(planned, state, *call);
    if (!ran.ok()) return ran.error();
    run.release_inputs(planned);  // what no reader needs goes back to the pool
  }
  return run.output();
}

}  // namespace aq
