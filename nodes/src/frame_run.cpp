// One evaluation of a compiled plan, step by step (frame_run.h).
#include "frame_run.h"

#include "builtin_nodes.h"

namespace aq {

PassClock::PassClock(NodeState& state, const EvalOptions& options)
    : state_(state), options_(options) {
  if (options_.finish_each_node) glFinish();  // earlier nodes' work is not this node's
  if (options_.measure_gpu_time) state_.mark_start();
  start_ = std::chrono::steady_clock::now();
}

void PassClock::stop() {
  if (options_.finish_each_node) glFinish();
  end_ = std::chrono::steady_clock::now();
  if (options_.measure_gpu_time) state_.mark_end();
}

NodeTiming PassClock::timing(const std::string& id, const NodeType& type) const {
  NodeTiming timing{id, type.name, 0,
                    std::chrono::duration<double, std::milli>(end_ - start_).count(), false};
  if (options_.measure_gpu_time) timing.gpu_ms = state_.marked_gpu_ms();
  return timing;
}

FrameRun::FrameRun(EvaluatorParts parts, const Graph& graph, const Plan& plan,
                   const EvalOptions& options, uint32_t gl_generation)
    : parts_(parts),
      graph_(graph),
      plan_(plan),
      options_(options),
      frame_(frame_constants(graph, plan, options, parts.host.table(), gl_generation)) {
  for (const auto& planned : plan.nodes) {
    readers_[planned.id] = planned.readers;
    varies_[planned.id] = planned.varies;
  }
}

NodeState& FrameRun::state_of(const PlannedNode& planned) {
  NodeState& state = parts_.states[planned.id];
  state.type = planned.type;
  const size_t outputs = planned.type->outputs.size();
  if (state.images.size() != outputs) {
    state.images.assign(outputs, nullptr);
    state.scenes.assign(outputs, nullptr);
    state.valid = false;
  }
  return state;
}

Result<NodeCall> FrameRun::prepare(const PlannedNode& planned) {
  return prepare_node_call(planned, graph_.nodes.at(planned.id), frame_, parts_.states);
}

bool FrameRun::tail_into_resample(const PlannedNode& planned, const TextureRef& input) const {
  // The output's pointwise tail runs in the pass that resamples a proxy render's output.
  const PlannedPass* pass = planned.deferred ? nullptr : plan_.pass_of(planned.id);
  return pass != nullptr && pass->resamples && input &&
         input->image.width == frame_.working.width && input->image.height == frame_.working.height;
}

bool FrameRun::reusable(const NodeState& state, const NodeCall& call) const {
  return state.valid && state.key == call.key;
}

Result<std::shared_ptr<FusedChain>> FrameRun::fuse(const PlannedNode& planned, NodeState& state,
                                                   NodeCall& call) {
  // A deferred node only records its stage; the node reading it runs the chain.
  const NodeType& type = *planned.type;
  const Node& node = graph_.nodes.at(planned.id);
  std::shared_ptr<FusedChain> chain;
  if (type.fusable != nullptr && node.inputs.count(type.inputs[0].name) != 0) {
    const std::string& source = node.inputs.at(type.inputs[0].name).node;
    if (auto found = chains_.find(source); found != chains_.end()) {
      chain = found->second;
      chains_.erase(found);
    }
  }
  if (planned.producer)
    return start_producer_chain(planned, state, std::move(call), frame_, parts_.host);
  // Nodes without inputs (image_input, generators) have no first image.
  const std::vector<TextureRef>& images = call.inputs.images;
  const TextureRef chain_input = chain ? chain->input : (images.empty() ? TextureRef() : images[0]);
  const bool joins = planned.deferred || ((chain || tail_into_resample(planned, chain_input)) &&
                                          !reusable(state, call));
  if (joins) {
    if (auto appended = append_stage(chain, planned, state, std::move(call), frame_, parts_.host);
        !appended.ok())
      return appended.error();
  }
  return chain;
}

Status FrameRun::defer(const PlannedNode& planned, NodeState& state, const NodeCall& call,
                       std::shared_ptr<FusedChain> chain) {
  for (auto& image : state.images) image.reset();
  state.valid = false;
  state.key = call.key;
  chains_[planned.id] = std::move(chain);
  NodeTiming timing{planned.id, planned.type->name, 0, 0, false};
  timing.fused = true;
  parts_.timings.push_back(timing);
  return Ok{};
}

Status FrameRun::reuse(const PlannedNode& planned) {
  parts_.timings.push_back(NodeTiming{planned.id, planned.type->name, 0, 0, true});
  return Ok{};
}

Status FrameRun::run_chain(const PlannedNode& planned, NodeState& state, const NodeCall& call,
                           FusedChain& chain) {
  const std::string& id = planned.id;
  const NodeType& type = *planned.type;
  // A producer draws at the working size; a fused shader at its input's, or the graph's when it
  // resamples a proxy render's output.
  int width = frame_.working.width, height = frame_.working.height;
  if (!chain.producer) {
    const bool resample = tail_into_resample(planned, chain.input);
    width = resample ? frame_.settings->width : chain.input->image.width;
    height = resample ? frame_.settings->height : chain.input->image.height;
  }
  PassClock clock(state, options_);
  const uint64_t previous_key = state.key;
  Result<TextureRef> fused =
      run_fused_pass(chain, planned, frame_.format, width, height, parts_.fuser, parts_.host);
  clock.stop();
  HostServices::reset_gl_state();
  ++parts_.run_counts[id];
  const std::string errors = stage_errors(chain);
  if (!fused.ok() || !errors.empty()) {
    state.valid = false;
    state.seen = false;  // what a failed call left in kept outputs is unknown
    if (chain.producer) chain.producer->state->seen = false;
    for (auto& stage : chain.stages) stage->call.state->seen = false;
    return make_error(errors.empty()
                          ? "node '" + id + "' (" + type.name + "), fused pass: " + fused.message()
                          : errors);
  }
  for (auto& image : state.images) image.reset();
  state.images[0] = *fused;
  state.key = call.key;
  state.valid = true;
  finish_chain_damage(chain, state, previous_key);
  NodeTiming timing = clock.timing(id, type);
  timing.redrawn = state.redrawn;
  parts_.timings.push_back(timing);
  return Ok{};
}

Status FrameRun::run_node(const PlannedNode& planned, NodeState& state, NodeCall& call) {
  const std::string& id = planned.id;
  const NodeType& type = *planned.type;
  CallState host_call;
  host_call.host = &parts_.host;
  host_call.state = &state;
  host_call.node_id = id;
  host_call.input_refs = &call.inputs.images;
  host_call.stored_formats = &planned.stored_formats;
  host_call.axis_deferrable = &planned.axis_deferrable;
  host_call.outputs_read = &planned.outputs_read;
  host_call.working_format = frame_.format;
  host_call.sources = &call.inputs.sources;
  host_call.input_keys = &call.inputs.keys;
  host_call.self_key = call.self_key;
  host_call.damage_key = call.damage_key;
  begin_damage_call(host_call, type.outputs.size());
  const uint64_t previous_key = state.key;
  aq_process_ctx ctx{};
  fill_process_ctx(ctx, frame_, host_call, call.inputs.values, call.params.params);
  if (!call.inputs.lists.empty()) ctx.input_lists = call.inputs.lists.data();
  ctx.input_keys = call.inputs.keys.data();

  for (auto& image : state.images) image.reset();
  for (auto& scene : state.scenes) scene = nullptr;
  PassClock clock(state, options_);
  int status = AQ_OK;
  if (type.desc == nullptr) {
    status = run_builtin(type, state.builtin, ctx, options_, parts_.host.pool(), &state.images,
                         &host_call.error);
  } else {
    if (auto created = ensure_instance(id, type, state, frame_.host); !created.ok()) return created;
    status = type.desc->process(state.instance, &ctx);
  }
  clock.stop();
  HostServices::reset_gl_state();
  host_call.scratch.clear();
  parts_.timings.push_back(clock.timing(id, type));
  ++parts_.run_counts[id];
  if (status != AQ_OK || !host_call.error.empty()) {
    state.valid = false;
    state.seen = false;
    for (auto& image : state.images) image.reset();
    return make_error("node '" + id + "' (" + type.name + "): " +
                      (host_call.error.empty() ? "failed without a message" : host_call.error));
  }
  if (auto checked = check_outputs(planned, state, host_call); !checked.ok()) return checked;
  finish_damage_call(state, host_call, previous_key);
  parts_.timings.back().redrawn = state.redrawn;
  state.key = call.key;
  state.valid = true;
  return Ok{};
}

// Every output was produced, in the layout the plan promised its readers; an encoded HDR image
// reaches only readers that decode it: one a plugin passed through to an output the plan keeps
// in the working format is decoded here.
Status FrameRun::check_outputs(const PlannedNode& planned, NodeState& state,
                               const CallState& call) {
  const std::string where = "node '" + planned.id + "' (" + planned.type->name + "): ";
  const auto& outputs = planned.type->outputs;
  for (size_t o = 0; o < outputs.size(); ++o) {
    bool missing = outputs[o].type == AQ_PORT_IMAGE ? !state.images[o] : state.scenes[o] == nullptr;
    if (missing) {
      state.valid = false;
      return make_error(where + "produced no output '" + outputs[o].name +
                        "' (a plugin bug: report it to its author)");
    }
  }
  for (size_t o = 0; o < outputs.size(); ++o) {
    const TextureRef& image = state.images[o];
    const uint32_t stored = call.stored_format(static_cast<uint32_t>(o));
    const bool blocks_stored = stored == AQ_FORMAT_RGBA8_HDR_BLOCKS;
    if (image && (image->image.format == AQ_FORMAT_RGBA8_HDR_BLOCKS) != blocks_stored) {
      state.valid = false;
      return make_error(where + "output '" + outputs[o].name +
                        "' is not in the 2 x 2 blocks its readers were promised, or is in "
                        "blocks they were not (a plugin bug: report it to its author)");
    }
    if (!image || image->image.format != AQ_FORMAT_RGBA8_HDR || stored == AQ_FORMAT_RGBA8_HDR)
      continue;
    auto decoded = parts_.fuser.run(parts_.host.shaders(), parts_.host.pool(), {}, image,
                                    image->image.width, image->image.height, frame_.format);
    if (!decoded.ok()) return make_error("node '" + planned.id + "': " + decoded.error().message);
    state.images[o] = *decoded;
  }
  return Ok{};
}

bool FrameRun::keeps(const std::string& id) const {
  if (options_.retain_outputs) return true;
  auto varies = varies_.find(id);
  return options_.retain_static_outputs && !(varies != varies_.end() && varies->second);
}

void FrameRun::release_inputs(const PlannedNode& planned) {
  // Inputs read for the last time go back to the pool, except static results that the next
  // frame will reuse.
  if (options_.retain_outputs) return;
  for (const auto& [port, source] : graph_.nodes.at(planned.id).inputs) {
    if (--readers_[source.node] == 0 && !keeps(source.node)) {
      NodeState& producer = parts_.states[source.node];
      for (auto& image : producer.images) image.reset();
      producer.valid = false;
    }
  }
}

Result<TextureRef> FrameRun::output() {
  const PortRef& target = plan_.output;
  NodeState& last = parts_.states[target.node];
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
  if (!keeps(target.node)) {
    for (auto& image : last.images) image.reset();
    last.valid = false;
  }
  return resample_output(result);
}

// A proxy render's output (working size) goes back to the graph's size.
Result<TextureRef> FrameRun::resample_output(const TextureRef& result) {
  const PixelSize& working = frame_.working;
  const Settings& settings = *frame_.settings;
  if (!result || result->image.width != working.width || result->image.height != working.height)
    return result;
  const uint32_t out_format = result->image.format;
  const bool filterable = out_format == AQ_FORMAT_RGBA16F || out_format == AQ_FORMAT_RGBA32F ||
                          out_format == AQ_FORMAT_R32F || out_format == AQ_FORMAT_RGBA8;
  if (!filterable || (working.width == settings.width && working.height == settings.height)) {
    return result;  // ids and depth stay at the working size: they cannot be filtered
  }
  auto resampled = parts_.fuser.run(parts_.host.shaders(), parts_.host.pool(), {}, result,
                                    settings.width, settings.height, out_format);
  HostServices::reset_gl_state();
  if (!resampled.ok())
    return make_error("resampling the output to the graph's size: " + resampled.message());
  return *resampled;
}

}  // namespace aq
