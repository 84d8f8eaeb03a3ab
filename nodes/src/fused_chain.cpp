// Pointwise fusion at execution time (fused_chain.h).
#include "fused_chain.h"

#include <cstddef>

#include "hash.h"

namespace aq {

Status ensure_instance(const std::string& id, const NodeType& type, NodeState& state,
                       const aq_host* host) {
  if (state.instance != nullptr || type.desc == nullptr) return Ok{};
  state.instance = type.desc->create(host);
  if (state.instance == nullptr) {
    return make_error("node '" + id + "' (" + type.name +
                      "): the plugin could not create the node (out of memory?)");
  }
  return Ok{};
}

namespace {

// Moves the node's call into `kept` and points its context at what `kept` now owns.
void keep_call(KeptCall& kept, const PlannedNode& planned, NodeState& state, NodeCall&& call,
               const FrameConstants& frame, HostServices& host) {
  kept.type = planned.type;
  kept.params = std::move(call.params.params);
  kept.strings = std::move(call.params.strings);
  kept.inputs = std::move(call.inputs.values);
  kept.call.host = &host;
  kept.call.state = &state;
  kept.call.node_id = planned.id;
  fill_process_ctx(kept.ctx, frame, kept.call, kept.inputs, kept.params);
  kept.input_keys = std::move(call.inputs.keys);
  kept.ctx.input_keys = kept.input_keys.data();
  kept.sources = std::move(call.inputs.sources);
  kept.call.sources = &kept.sources;
  kept.call.input_keys = &kept.input_keys;
  kept.call.self_key = call.self_key;
  kept.call.damage_key = call.damage_key;
}

}  // namespace

Result<std::shared_ptr<FusedChain>> start_producer_chain(const PlannedNode& planned,
                                                         NodeState& state, NodeCall&& call,
                                                         const FrameConstants& frame,
                                                         HostServices& host) {
  if (auto created = ensure_instance(planned.id, *planned.type, state, frame.host); !created.ok())
    return created.error();
  auto chain = std::make_shared<FusedChain>();
  chain->producer = std::make_unique<FusedChain::Producer>();
  FusedChain::Producer& producer = *chain->producer;
  producer.state = &state;
  producer.input_refs = std::move(call.inputs.images);
  producer.links = std::move(call.inputs.links);
  producer.lists = std::move(call.inputs.lists);
  producer.call.input_refs = &producer.input_refs;
  producer.call.working_format = frame.format;
  keep_call(producer, planned, state, std::move(call), frame, host);
  if (!producer.lists.empty()) producer.ctx.input_lists = producer.lists.data();
  return chain;
}

Status append_stage(std::shared_ptr<FusedChain>& chain, const PlannedNode& planned,
                    NodeState& state, NodeCall&& call, const FrameConstants& frame,
                    HostServices& host) {
  const NodeType& type = *planned.type;
  if (!chain) {
    chain = std::make_shared<FusedChain>();
    chain->input = call.inputs.images[0];
    if (!chain->input) {
      return make_error("node '" + planned.id + "' (" + type.name + "): input '" +
                        type.inputs[0].name + "' has no image");
    }
  }
  if (auto created = ensure_instance(planned.id, type, state, frame.host); !created.ok())
    return created;
  auto stage = std::make_unique<FusedChain::Stage>();
  stage->instance = state.instance;
  stage->input_refs = call.inputs.images;
  keep_call(*stage, planned, state, std::move(call), frame, host);
  chain->stages.push_back(std::move(stage));
  return Ok{};
}

uint32_t chain_result_format(const std::vector<uint32_t>& stored, uint32_t working) {
  return !stored.empty() && stored[0] == AQ_FORMAT_RGBA8_HDR ? stored[0] : working;
}

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

namespace {

// The stages as the fused shader applies them: each one's function, instance, context and its
// inputs after the first, bound as samplers.
std::vector<FusedStage> fused_stages(const FusedChain& chain) {
  std::vector<FusedStage> stages;
  for (const auto& stage : chain.stages) {
    FusedStage fused_stage{stage->type->fusable, stage->instance, &stage->ctx, {}};
    for (size_t k = 1; k < stage->inputs.size(); ++k)
      fused_stage.samplers.emplace_back(stage->type->inputs[k].name,
                                        stage->inputs[k].image.texture);
    stages.push_back(std::move(fused_stage));
  }
  return stages;
}

// Epilogue fusion: runs the producer's process() with `stages` as the epilogue of the draw
// that writes its output 0, which becomes the chain's result (stored as the chain's last
// node's output is: `stored`). A producer that applied no epilogue (it passed its input
// through, or its method's shaders do not call aq_epilogue) gets the chain as a pass of its
// own, so the result never depends on whether the node cooperated.
Result<TextureRef> run_producer(FusedChain::Producer& producer,
                                const std::vector<FusedStage>& stages,
                                const std::vector<uint32_t>& stored, uint32_t format,
                                PointwiseFuser& fuser, HostServices& host) {
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
  // The host's own pass reads and writes pixels: a chain stored in 2 x 2 blocks is the
  // producer's promise (AQ_PORT_BLOCKS on its output) to apply the epilogue itself.
  if (out->image.format == AQ_FORMAT_RGBA8_HDR_BLOCKS ||
      (!stored.empty() && stored[0] == AQ_FORMAT_RGBA8_HDR_BLOCKS))
    return make_error(where +
                      ": wrote its output in 2 x 2 blocks without applying the epilogue "
                      "(a plugin bug: an AQ_PORT_BLOCKS output of an AQ_NODE_EPILOGUE node "
                      "must call aq_epilogue_at on each pixel it writes)");
  return fuser.run(host.shaders(), host.pool(), stages, out, out->image.width, out->image.height,
                   chain_result_format(stored, format));
}

}  // namespace

Result<TextureRef> run_fused_pass(FusedChain& chain, const PlannedNode& planned, uint32_t format,
                                  int width, int height, PointwiseFuser& fuser,
                                  HostServices& host) {
  const std::vector<FusedStage> stages = fused_stages(chain);
  if (!chain.producer) {
    return fuser.run(host.shaders(), host.pool(), stages, chain.input, width, height,
                     chain_result_format(planned.stored_formats, format));
  }
  FusedChain::Producer& producer = *chain.producer;
  producer.call.epilogue_damage = epilogue_damage_of(chain, width, height);
  // What the producer's kept output holds depends on the epilogue it applied.
  uint64_t& producer_key = producer.call.self_key;
  producer_key = hash_string(producer_key, "epilogue");
  uint64_t& producer_damage_key = producer.call.damage_key;
  producer_damage_key = hash_string(producer_damage_key, "epilogue");
  for (const auto& stage : chain.stages) {
    producer_key = hash_string(producer_key, stage->call.node_id);
    producer_damage_key = hash_string(producer_damage_key, stage->call.node_id);
  }
  auto result = run_producer(producer, stages, planned.stored_formats, format, fuser, host);
  producer.call.epilogue = nullptr;  // `stages` ends here
  return result;
}

std::string stage_errors(const FusedChain& chain) {
  std::string errors;
  for (const auto& stage : chain.stages) {
    if (!stage->call.error.empty()) {
      errors += "node '" + stage->call.node_id + "' (" + stage->type->name +
                "): " + stage->call.error + "\n";
    }
  }
  return errors.empty() ? errors : errors.substr(0, errors.size() - 1);
}

void finish_chain_damage(FusedChain& chain, NodeState& state, uint64_t previous_key) {
  // What each stage saw; the chain's result changed where its producer redrew.
  for (auto& stage : chain.stages)
    finish_damage_call(*stage->call.state, stage->call, stage->call.state->key);
  std::vector<std::optional<Region>> result_damage;
  if (chain.producer) {
    FusedChain::Producer& producer = *chain.producer;
    finish_damage_call(*producer.state, producer.call, producer.state->key);
    if (!producer.call.declared_damage.empty())
      result_damage.push_back(producer.call.declared_damage[0]);
  }
  record_output_damage(state, previous_key, result_damage, {});
}

}  // namespace aq
