// The aq_host services (see host_services.h), moved out of the evaluator so that evaluation
// (plan, then execution) and what plugins may ask of the host read as separate things.
#include "host_services.h"

#include "hash.h"
#include "host_image_service.h"

#include <aquarelle/core/gl_context.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace aq {

void NodeState::mark_start() {
  if (!timer_start) {
    timer_start = gl::make_query();
    timer_end = gl::make_query();
  }
  glQueryCounter(timer_start.get(), GL_TIMESTAMP);
}

void NodeState::mark_end() {
  glQueryCounter(timer_end.get(), GL_TIMESTAMP);
}

double NodeState::marked_gpu_ms() const {
  GLuint64 begin_ns = 0, end_ns = 0;
  glGetQueryObjectui64v(timer_start.get(), GL_QUERY_RESULT, &begin_ns);
  glGetQueryObjectui64v(timer_end.get(), GL_QUERY_RESULT, &end_ns);
  return end_ns > begin_ns ? static_cast<double>(end_ns - begin_ns) * 1e-6 : 0.0;
}

HostServices* HostServices::current_ = nullptr;

HostServices::HostServices(GlContext& context, TexturePool& pool) : context_(context), pool_(pool) {
  host_.abi_version = AQ_ABI_VERSION;
  host_.struct_size = sizeof(aq_host);
  host_.get_proc_address = &HostServices::get_proc_address;
  host_.fail = &HostServices::fail;
  host_.log = &HostServices::log;
  host_.program = &HostServices::program;
  host_.output_image = &HostServices::output_image;
  host_.pass_through = &HostServices::pass_through;
  host_.output_scene = &HostServices::output_scene;
  host_.scratch_image = &HostServices::scratch_image;
  host_.bind_targets = &HostServices::bind_targets;
  host_.draw_fullscreen = &HostServices::draw_fullscreen;
  host_.read_image = &host_read_image;
  host_.output_kept = &HostServices::output_kept;
  host_.input_damage = &HostServices::input_damage;
  host_.epilogue_damage = &HostServices::epilogue_damage;
  host_.set_output_damage = &HostServices::set_output_damage;
  host_.set_draw_region = &HostServices::set_draw_region;
  host_.set_output_bounds = &HostServices::set_output_bounds;
  host_.input_bounds = &HostServices::input_bounds;
  host_.may_defer_axis = &HostServices::may_defer_axis;
  host_.defer_axis = &HostServices::defer_axis;
  host_.input_deferred_axis = &HostServices::input_deferred_axis;
  host_.output_read = &HostServices::output_read;
  empty_vao_ = gl::make_vertex_array();
  GLuint framebuffer = 0;
  glCreateFramebuffers(1, &framebuffer);  // created, not just named: DSA calls need that
  framebuffer_ = gl::Framebuffer(framebuffer);
}

void* HostServices::get_proc_address(const char* name) {
  return current_ != nullptr ? current_->context_.get_proc_address(name) : nullptr;
}

void HostServices::fail(void* data, const char* message) {
  fail_call(*static_cast<CallState*>(data), message != nullptr ? message : "(no message)");
}

void fail_call(CallState& call, const std::string& message) {
  if (!call.error.empty()) call.error += "\n";
  call.error += message;
}

void HostServices::log(void* data, int level, const char* message) {
  auto* call = static_cast<CallState*>(data);
  std::fprintf(stderr, "%s: node '%s': %s\n", level > 0 ? "warning" : "info", call->node_id.c_str(),
               message);
}

uint32_t HostServices::program(void* data, const aq_shader_source* vertex,
                               const aq_shader_source* fragment) {
  auto* call = static_cast<CallState*>(data);
  // An AQ_NODE_EPILOGUE node's fragment shaders get aq_epilogue(): the identity, or the
  // pointwise chain fused into its last draw.
  const bool epilogue = fragment != nullptr && fragment->text != nullptr &&
                        call->state != nullptr && call->state->type != nullptr &&
                        call->state->type->takes_epilogue();
  std::string text;
  aq_shader_source with_epilogue{};
  if (epilogue) {
    text = epilogue_source(call->epilogue) + "#line 1\n" + fragment->text;
    with_epilogue = aq_shader_source{fragment->name, text.c_str(), nullptr};
  }
  auto result = call->host->shaders_.program(vertex, epilogue ? &with_epilogue : fragment);
  if (!result.ok()) {
    fail(data, result.message().c_str());
    return 0;
  }
  return *result;
}

bool HostServices::valid_size(CallState* call, int32_t width, int32_t height) {
  GLint limit = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &limit);
  if (width < 1 || height < 1 || width > limit || height > limit) {
    fail_call(*call, "cannot make a " + std::to_string(width) + "x" + std::to_string(height) +
                         " texture: sizes run from 1x1 to " + std::to_string(limit) + "x" +
                         std::to_string(limit) + " on this GL implementation");
    return false;
  }
  return true;
}

// An unknown format would get an all-zero texture of some default kind: refuse it by name.
bool HostServices::valid_format(CallState* call, const char* function, uint32_t format) {
  if (format >= AQ_FORMAT_RGBA16F && format <= AQ_FORMAT_RGBA32UI) return true;
  fail_call(*call, std::string(function) + ": unknown image format " + std::to_string(format) +
                       " (aq_format in plugin.h: 1 RGBA16F, 2 RGBA32F, 3 R32F, 4 DEPTH32F, "
                       "5 R32UI, 6 RGBA8, 7 RGBA8_HDR, 8 RGBA8_HDR_BLOCKS, 9 RGBA32UI; use "
                       "ctx.working_format "
                       "for the graph's precision)");
  return false;
}

int HostServices::output_image(void* data, uint32_t index, int32_t width, int32_t height,
                               uint32_t format, aq_image* out) {
  auto* call = static_cast<CallState*>(data);
  NodeState& state = *call->state;
  if (index >= state.images.size() || state.type->outputs[index].type != AQ_PORT_IMAGE) {
    fail_call(*call, "output_image: no image output with index " + std::to_string(index));
    return AQ_ERROR;
  }
  if (!valid_format(call, "output_image", format)) return AQ_ERROR;
  if (!valid_size(call, width, height)) return AQ_ERROR;
  // Bandwidth by need: a colour output is stored in the narrower format the plan chose for
  // its readers. An encoded HDR output goes only to readers that decode it: a plugin asking
  // for one the plan did not choose (output_like an encoded input) gets the working format.
  const uint32_t stored = call->stored_format(index);
  const bool encoded = format == AQ_FORMAT_RGBA8_HDR || format == AQ_FORMAT_RGBA8_HDR_BLOCKS;
  const bool colour = format == AQ_FORMAT_RGBA16F || format == AQ_FORMAT_RGBA32F || encoded;
  if (colour && stored != 0) {
    format = stored;
  } else if (encoded) {
    format = call->working_format;
  }
  // Tagged with the instance and the output once the instance asked (output_kept), so that
  // it gets the same texture back on its next call and is told it still holds its content.
  const uint64_t writer = output_writer(state, index);
  bool kept = false;
  state.images[index] = call->host->pool_.acquire(width, height, format, writer, &kept);
  if (call->kept_outputs.size() <= index) call->kept_outputs.resize(index + 1, false);
  call->kept_outputs[index] = kept && state.instance != nullptr;
  if (call->acquired_outputs.size() <= index) call->acquired_outputs.resize(index + 1, false);
  call->acquired_outputs[index] = true;
  *out = state.images[index]->image;
  return AQ_OK;
}

uint64_t output_writer(const NodeState& state, uint32_t index) {
  return state.writer_tag != 0 ? hash_value(hash_value(kHashSeed, state.writer_tag), index + 1) : 0;
}

int HostServices::output_kept(void* data, uint32_t index) {
  auto* call = static_cast<CallState*>(data);
  // A tag no other instance ever had, so that a new instance at the address of a destroyed
  // one never gets that one's textures back as its own.
  static std::atomic<uint64_t> next_tag{0};
  NodeState& state = *call->state;
  if (state.writer_tag == 0) {
    state.writer_tag = ++next_tag;
    // The outputs this call already has become the instance's, so that its next call gets
    // them back (the ones it acquires from now on are tagged as they are handed out).
    for (uint32_t o = 0; o < state.images.size() && o < call->acquired_outputs.size(); ++o) {
      if (call->acquired_outputs[o] && state.images[o])
        call->host->pool_.claim(*state.images[o], output_writer(state, o));
    }
  }
  return index < call->kept_outputs.size() && call->kept_outputs[index] ? 1 : 0;
}

int HostServices::pass_through(void* data, uint32_t index, uint32_t input_index) {
  auto* call = static_cast<CallState*>(data);
  NodeState& state = *call->state;
  if (index >= state.images.size() || call->input_refs == nullptr ||
      input_index >= call->input_refs->size() || !(*call->input_refs)[input_index]) {
    fail_call(*call, "pass_through: no such image output or connected image input");
    return AQ_ERROR;
  }
  state.images[index] = (*call->input_refs)[input_index];
  if (index < call->acquired_outputs.size()) call->acquired_outputs[index] = false;
  return AQ_OK;
}

int HostServices::output_scene(void* data, uint32_t index, const aq_scene* scene) {
  auto* call = static_cast<CallState*>(data);
  NodeState& state = *call->state;
  if (index >= state.scenes.size() || state.type->outputs[index].type != AQ_PORT_SCENE) {
    fail_call(*call, "output_scene: no scene output with index " + std::to_string(index));
    return AQ_ERROR;
  }
  state.scenes[index] = scene;
  return AQ_OK;
}

namespace {

// Fills `image` with values no pass computes: bit patterns for integer textures, a saturated
// off-colour with alpha 0.5 for the others.
void poison_texture(const aq_image& image) {
  const bool integer = image.format == AQ_FORMAT_RGBA8_HDR_BLOCKS ||
                       image.format == AQ_FORMAT_R32UI || image.format == AQ_FORMAT_RGBA32UI;
  if (integer) {
    const GLuint words[4] = {0x7f3f1f0fu, 0x12345678u, 0x9abcdef0u, 0x0f1f3f7fu};
    glClearTexImage(image.texture, 0, GL_RGBA_INTEGER, GL_UNSIGNED_INT, words);
  } else {
    const float colour[4] = {0.37f, 0.91f, 0.05f, 0.5f};
    glClearTexImage(image.texture, 0, GL_RGBA, GL_FLOAT, colour);
  }
}

}  // namespace

int HostServices::scratch_image(void* data, int32_t width, int32_t height, uint32_t format,
                                aq_image* out) {
  auto* call = static_cast<CallState*>(data);
  if (!valid_format(call, "scratch_image", format)) return AQ_ERROR;
  if (!valid_size(call, width, height)) return AQ_ERROR;
  call->scratch.push_back(call->host->pool_.acquire(width, height, format));
  *out = call->scratch.back()->image;
  // AQUARELLE_POISON_SCRATCH=1 (tests, debugging): a scratch image arrives full of junk instead
  // of whatever its last user left, so a pass that reads pixels no pass of this call wrote shows
  // in the picture instead of reading last frame's values (often the right ones by chance).
  const char* poison = std::getenv("AQUARELLE_POISON_SCRATCH");  // per call: tests flip it
  if (poison != nullptr && std::string(poison) == "1") poison_texture(*out);
  return AQ_OK;
}

int HostServices::bind_targets(void* data, const aq_image* colors, uint32_t count,
                               const aq_image* depth) {
  auto* call = static_cast<CallState*>(data);
  HostServices& host = *call->host;
  GLuint fbo = host.framebuffer_.get();
  GLint max_attachments = 8;
  glGetIntegerv(GL_MAX_COLOR_ATTACHMENTS, &max_attachments);
  if (count > static_cast<uint32_t>(max_attachments)) {
    fail_call(*call, "bind_targets: too many colour targets");
    return AQ_ERROR;
  }
  std::vector<GLenum> buffers;
  for (uint32_t i = 0; i < count; ++i) {
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0 + i, colors[i].texture, 0);
    buffers.push_back(GL_COLOR_ATTACHMENT0 + i);
  }
  for (GLuint i = count; i < host.attached_colors_; ++i) {
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0 + i, 0, 0);
  }
  host.attached_colors_ = count;
  glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depth != nullptr ? depth->texture : 0, 0);
  if (count > 0) {
    glNamedFramebufferDrawBuffers(fbo, static_cast<GLsizei>(count), buffers.data());
  } else {
    glNamedFramebufferDrawBuffer(fbo, GL_NONE);
  }
  GLenum status = glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    char text[96];
    std::snprintf(text, sizeof(text), "bind_targets: framebuffer incomplete (0x%04X)", status);
    fail_call(*call, text);
    return AQ_ERROR;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  const aq_image& size_of = count > 0 ? colors[0] : *depth;
  int32_t width = 0, height = 0;
  aq_image_texels(&size_of, &width, &height);  // a target in 2 x 2 blocks is drawn per block
  glViewport(0, 0, width, height);
  return AQ_OK;
}

void HostServices::draw_fullscreen(void* data) {
  auto* call = static_cast<CallState*>(data);
  if (call->epilogue != nullptr && !call->epilogue->empty() && !apply_epilogue(call)) return;
  glBindVertexArray(call->host->empty_vao_.get());
  if (call->draw_region.all()) {
    glDrawArrays(GL_TRIANGLES, 0, 3);
  } else {
    call->host->draw_rects(call->draw_region.rects());
  }
  glBindVertexArray(0);
}

// The full-screen triangle once per rect, scissored: llvmpipe bins a scissored triangle only
// into the tiles the scissor box touches. Each rect also costs it a fixed time whatever it
// covers: about 9 µs of GL time as a draw call of its own, 5 µs in an instanced draw (40 tiny
// rects measured), and a frame of the flagship draws about 570 rects. So where the program is
// the host's full-screen one, whose instance i goes to viewport i, up to GL_MAX_VIEWPORTS rects
// share one draw, each in its viewport's scissor box: the same triangle, so the same pixels and
// interpolated values.
void HostServices::draw_rects(const std::vector<PixelRect>& rects) {
  GLint program = 0;
  glGetIntegerv(GL_CURRENT_PROGRAM, &program);
  const size_t batch = shaders_.fullscreen(static_cast<GLuint>(program)) ? viewport_batch() : 1;
  glEnable(GL_SCISSOR_TEST);
  if (batch > 1) {
    std::vector<GLint> boxes;
    for (size_t first = 0; first < rects.size(); first += batch) {
      const size_t count = std::min(batch, rects.size() - first);
      boxes.clear();
      for (size_t i = first; i < first + count; ++i)
        boxes.insert(boxes.end(), {rects[i].x0, rects[i].y0, rects[i].x1 - rects[i].x0,
                                   rects[i].y1 - rects[i].y0});
      glScissorArrayv(0, static_cast<GLsizei>(count), boxes.data());
      glDrawArraysInstanced(GL_TRIANGLES, 0, 3, static_cast<GLsizei>(count));
    }
  } else {
    for (const PixelRect& r : rects) {
      glScissor(r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0);
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  }
  glDisable(GL_SCISSOR_TEST);
}

// How many rects one draw may carry: GL_MAX_VIEWPORTS where the full-screen vertex shader can
// choose the viewport (GL_ARB_shader_viewport_layer_array), else 1. AQUARELLE_DRAW_BATCH=0: 1
// (one draw per rect, to measure the difference).
size_t HostServices::viewport_batch() {
  if (viewport_batch_ == 0) {
    viewport_batch_ = 1;
    const char* lever = std::getenv("AQUARELLE_DRAW_BATCH");
    GLint extensions = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &extensions);
    bool layer_array = false;
    for (GLint i = 0; i < extensions && !layer_array; ++i) {
      const auto* name = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, i));
      layer_array = name != nullptr && std::string(name) == "GL_ARB_shader_viewport_layer_array";
    }
    GLint viewports = 0;
    glGetIntegerv(GL_MAX_VIEWPORTS, &viewports);
    if (layer_array && viewports > 1 && (lever == nullptr || std::string(lever) != "0"))
      viewport_batch_ = static_cast<size_t>(viewports);
  }
  return viewport_batch_;
}

namespace {

int write_rects(const Region& region, aq_rect* rects, uint32_t capacity) {
  if (region.all() || region.rects().size() > capacity) return -1;
  for (size_t i = 0; i < region.rects().size(); ++i) {
    const PixelRect& r = region.rects()[i];
    rects[i] = aq_rect{r.x0, r.y0, r.x1, r.y1};
  }
  return static_cast<int>(region.rects().size());
}

}  // namespace

// AQUARELLE_DAMAGE=0: every input changed everywhere, so nodes redraw all of their outputs
// (the bench's lever table measures damage tracking off without a rebuild).
static bool damage_tracking_enabled() {
  static const bool enabled = [] {
    const char* value = std::getenv("AQUARELLE_DAMAGE");
    return value == nullptr || std::string(value) != "0";
  }();
  return enabled;
}

Region input_damage_of(const CallState& call, uint32_t index) {
  if (!damage_tracking_enabled()) return Region::everything();
  const NodeState& self = *call.state;
  if (!self.seen || self.seen_damage_key != call.damage_key || call.input_keys == nullptr ||
      call.sources == nullptr || index >= call.input_keys->size() ||
      index >= call.sources->size() || index >= self.seen_input_keys.size())
    return Region::everything();
  const uint64_t now = (*call.input_keys)[index];
  const uint64_t seen = self.seen_input_keys[index];
  if (now == 0) return Region::everything();
  if (now == seen) return Region();
  // The source ran since: its damage tells where, if it is relative to what this node saw.
  const DamageSource& source = (*call.sources)[index];
  if (source.state == nullptr || source.output >= source.state->output_damage.size())
    return Region::everything();
  if (hash_string(hash_value(kHashSeed, source.state->previous_key), source.port) != seen)
    return Region::everything();
  return source.state->output_damage[source.output];
}

void begin_damage_call(CallState& call, size_t output_count) {
  call.draw_region = Region::everything();
  call.declared_damage.assign(output_count, std::nullopt);
  call.declared_bounds.assign(output_count, std::nullopt);
  call.declared_deferral.assign(output_count, std::nullopt);
}

void record_output_damage(NodeState& state, uint64_t previous_key,
                          const std::vector<std::optional<Region>>& damage,
                          const std::vector<std::optional<Region>>& bounds) {
  state.previous_key = previous_key;
  state.output_damage.assign(state.images.size(), Region::everything());
  state.output_bounds.assign(state.images.size(), Region::everything());
  state.output_deferred.assign(state.images.size(), std::nullopt);
  int64_t redrawn = 0, total = 0;
  for (size_t o = 0; o < state.images.size(); ++o) {
    if (o < bounds.size() && bounds[o]) state.output_bounds[o] = *bounds[o];
    if (o < damage.size() && damage[o]) state.output_damage[o] = *damage[o];
    const TextureRef& image = state.images[o];
    if (!image) continue;  // a scene
    redrawn += state.output_damage[o].area(image->image.width, image->image.height);
    total += int64_t{image->image.width} * image->image.height;
  }
  state.redrawn = total > 0 ? static_cast<double>(redrawn) / static_cast<double>(total) : -1.0;
}

void finish_damage_call(NodeState& state, const CallState& call, uint64_t previous_key) {
  state.seen = true;
  state.seen_self_key = call.self_key;
  state.seen_damage_key = call.damage_key;
  state.seen_input_keys = call.input_keys != nullptr ? *call.input_keys : std::vector<uint64_t>();
  record_output_damage(state, previous_key, call.declared_damage, call.declared_bounds);
  for (size_t o = 0; o < state.output_deferred.size() && o < call.declared_deferral.size(); ++o)
    state.output_deferred[o] = call.declared_deferral[o];
}

int HostServices::input_damage(void* data, uint32_t index, aq_rect* rects, uint32_t capacity) {
  const auto* call = static_cast<const CallState*>(data);
  return write_rects(input_damage_of(*call, index), rects, capacity);
}

int HostServices::epilogue_damage(void* data, aq_rect* rects, uint32_t capacity) {
  const auto* call = static_cast<const CallState*>(data);
  if (call->epilogue == nullptr || call->epilogue->empty()) return 0;
  return write_rects(call->epilogue_damage, rects, capacity);
}

int HostServices::set_output_damage(void* data, uint32_t index, const aq_rect* rects,
                                    uint32_t count) {
  auto* call = static_cast<CallState*>(data);
  if (index >= call->declared_damage.size() || index >= call->kept_outputs.size() ||
      !call->kept_outputs[index]) {
    fail_call(*call, "set_output_damage: output " + std::to_string(index) +
                         " was not kept (output_kept is 0): it changed everywhere; redraw it all "
                         "and declare nothing (a plugin bug: report it to its author)");
    return AQ_ERROR;
  }
  Region region = region_of(rects, count);
  if (index == 0 && call->epilogue != nullptr && !call->epilogue->empty() &&
      !region.covers(call->epilogue_damage)) {
    fail_call(*call,
              "set_output_damage: output 0 runs a fused epilogue whose inputs changed outside the "
              "declared rects; add epilogue_damage to them (a plugin bug: report it to its "
              "author)");
    return AQ_ERROR;
  }
  call->declared_damage[index] = std::move(region);
  return AQ_OK;
}

int HostServices::set_output_bounds(void* data, uint32_t index, const aq_rect* rects,
                                    uint32_t count) {
  auto* call = static_cast<CallState*>(data);
  if (index >= call->declared_bounds.size()) {
    fail_call(*call, "set_output_bounds: no output with index " + std::to_string(index));
    return AQ_ERROR;
  }
  call->declared_bounds[index] = region_of(rects, count);
  return AQ_OK;
}

int HostServices::input_bounds(void* data, uint32_t index, aq_rect* rects, uint32_t capacity) {
  const auto* call = static_cast<const CallState*>(data);
  if (call->sources == nullptr || index >= call->sources->size()) return -1;
  const DamageSource& source = (*call->sources)[index];
  if (source.state == nullptr || source.output >= source.state->output_bounds.size()) return -1;
  return write_rects(source.state->output_bounds[source.output], rects, capacity);
}

int HostServices::output_read(void* data, uint32_t index) {
  const auto* call = static_cast<const CallState*>(data);
  const std::vector<bool>* read = call->outputs_read;
  return read == nullptr || read->empty() || index >= read->size() || (*read)[index] ? 1 : 0;
}

int HostServices::may_defer_axis(void* data, uint32_t index) {
  const auto* call = static_cast<const CallState*>(data);
  return call->axis_deferrable != nullptr && index < call->axis_deferrable->size() &&
                 (*call->axis_deferrable)[index]
             ? 1
             : 0;
}

int HostServices::defer_axis(void* data, uint32_t index, const aq_axis_pass* pass) {
  auto* call = static_cast<CallState*>(data);
  if (may_defer_axis(data, index) == 0 || index >= call->declared_deferral.size()) {
    fail_call(*call, "defer_axis: output " + std::to_string(index) +
                         " may not leave a pass to its reader (may_defer_axis is 0); run the "
                         "pass (a plugin bug: report it to its author)");
    return AQ_ERROR;
  }
  if (pass == nullptr || (pass->axis != 0 && pass->axis != 1) || pass->radius < 1 ||
      pass->radius > 4) {
    fail_call(*call,
              "defer_axis: the pass must have axis 0 or 1 and a radius of 1 to 4 (a "
              "plugin bug: report it to its author)");
    return AQ_ERROR;
  }
  call->declared_deferral[index] = *pass;
  return AQ_OK;
}

int HostServices::input_deferred_axis(void* data, uint32_t index, aq_axis_pass* pass) {
  const auto* call = static_cast<const CallState*>(data);
  if (call->sources == nullptr || index >= call->sources->size()) return 0;
  const DamageSource& source = (*call->sources)[index];
  if (source.state == nullptr || source.output >= source.state->output_deferred.size() ||
      !source.state->output_deferred[source.output])
    return 0;
  if (pass != nullptr) *pass = *source.state->output_deferred[source.output];
  return 1;
}

void HostServices::set_draw_region(void* data, const aq_rect* rects, uint32_t count) {
  auto* call = static_cast<CallState*>(data);
  call->draw_region = rects == nullptr ? Region::everything() : region_of(rects, count);
}

// A draw whose program calls aq_epilogue (its aq_epilogue_size uniform is live) gets the
// stages' uniforms; it must write the node's output 0, the only image the chain stands for.
bool HostServices::apply_epilogue(CallState* call) {
  GLint program = 0;
  glGetIntegerv(GL_CURRENT_PROGRAM, &program);
  if (program == 0 || glGetUniformLocation(static_cast<GLuint>(program), "aq_epilogue_size") < 0)
    return true;
  const TextureRef& output = call->state->images.empty() ? TextureRef() : call->state->images[0];
  GLint attached = 0;
  glGetNamedFramebufferAttachmentParameteriv(call->host->framebuffer_.get(), GL_COLOR_ATTACHMENT0,
                                             GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &attached);
  if (!output || static_cast<GLuint>(attached) != output->image.texture) {
    fail_call(*call,
              "a draw applied aq_epilogue but does not write output 0 (AQ_NODE_EPILOGUE: call it "
              "only on the value written to the node's first output)");
    return false;
  }
  if (!set_epilogue_uniforms(*call->epilogue, static_cast<GLuint>(program), output->image.width,
                             output->image.height)) {
    fail_call(*call, "setting the uniforms of the fused epilogue failed");
    return false;
  }
  ++call->epilogue_draws;
  return true;
}

void HostServices::reset_gl_state() {
  glUseProgram(0);
  glBindVertexArray(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDepthMask(GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  for (GLuint unit = 0; unit < 8; ++unit) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D, 0);
  }
  glActiveTexture(GL_TEXTURE0);
}

}  // namespace aq
