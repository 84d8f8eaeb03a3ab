// The viewer: evaluation of the viewed output and its display pass. See viewer.h.
#include "viewer.h"

#include "editor_actions.h"
#include "eval_policy.h"
#include "image_stats.h"
#include "item_rects.h"

#include <glad/gl.h>
#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

namespace aq::editor {

namespace {

// A full-screen triangle from gl_VertexID; v_uv spans 0..1 over the target.
constexpr const char* kVertexShader = R"(#version 450 core
out vec2 v_uv;
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  v_uv = p;
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

// Float images on unit 0, integer ids on unit 1: a sampler type never meets a texture of the
// other kind.
constexpr const char* kFragmentShader = R"(#version 450 core
in vec2 v_uv;
layout(location = 0) out vec4 o_color;
uniform sampler2D u_image;
uniform usampler2D u_ids;
uniform int u_mapping;   // 0 colour, 1 depth, 2 integer id, 3 id stored as float
uniform int u_channel;   // 0 rgb, 1 r, 2 g, 3 b, 4 a
uniform int u_srgb;
uniform float u_gain;
uniform vec2 u_range;

float to_srgb(float c) {
  c = clamp(c, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
}

vec3 id_colour(uint id) {
  if (id == 0u) return vec3(0.0);
  uint h = id * 747796405u + 2891336453u;
  h = ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;
  h = (h >> 22u) ^ h;
  return vec3(float(h & 255u), float((h >> 8) & 255u), float((h >> 16) & 255u)) / 255.0 * 0.8 + 0.2;
}

void main() {
  if (u_mapping == 2) {
    o_color = vec4(id_colour(texture(u_ids, v_uv).r), 1.0);
    return;
  }
  vec4 c = texture(u_image, v_uv);
  if (u_mapping == 3) {  // ids stored as floats
    o_color = vec4(id_colour(uint(max(round(c.r), 0.0))), 1.0);
    return;
  }
  if (u_mapping == 1) {
    float v = c.r;
    if (isnan(v) || isinf(v)) { o_color = vec4(1.0, 0.0, 1.0, 1.0); return; }
    float span = max(u_range.y - u_range.x, 1e-12);
    float t = clamp((v - u_range.x) / span, 0.0, 1.0);
    o_color = vec4(vec3(1.0 - t), 1.0);  // near is bright
    return;
  }
  vec3 rgb = c.rgb;
  if (u_channel == 1) rgb = vec3(c.r);
  if (u_channel == 2) rgb = vec3(c.g);
  if (u_channel == 3) rgb = vec3(c.b);
  if (u_channel == 4) rgb = vec3(c.a);
  if (any(isnan(rgb)) || any(isinf(rgb))) { o_color = vec4(1.0, 0.0, 1.0, 1.0); return; }
  rgb *= u_gain;
  if (u_srgb != 0) rgb = vec3(to_srgb(rgb.r), to_srgb(rgb.g), to_srgb(rgb.b));
  o_color = vec4(clamp(rgb, 0.0, 1.0), 1.0);
}
)";

GLuint compile(GLenum stage, const char* source, std::string* log) {
  GLuint shader = glCreateShader(stage);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char text[2048];
    glGetShaderInfoLog(shader, sizeof text, nullptr, text);
    *log += text;
    glDeleteShader(shader);
    return 0;
  }
  return shader;
}

bool is_single_channel_float(uint32_t format) {
  return format == AQ_FORMAT_R32F || format == AQ_FORMAT_DEPTH32F;
}

bool is_integer(uint32_t format) {
  return format == AQ_FORMAT_R32UI || format == AQ_FORMAT_RGBA32UI;
}

// "node 'blur' (blur): ..." → "blur"
std::string node_named_in(const std::string& message) {
  auto start = message.find("node '");
  if (start == std::string::npos) return "";
  start += 6;
  auto end = message.find('\'', start);
  return end == std::string::npos ? "" : message.substr(start, end - start);
}

}  // namespace

float linear_to_srgb(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

Viewer::Viewer(std::unique_ptr<EvalWorker> worker) : worker_(std::move(worker)) {}

Viewer::~Viewer() {
  worker_.reset();  // joins the thread; an image it made and nobody took is deleted there
}

Viewer::Mapping Viewer::current_mapping() const {
  if (!has_image_) return Mapping::kColor;
  const aq_image& image = image_;
  // Only an id mapping can read an integer texture (packed words show as ids of their first).
  if (is_integer(image.format)) return Mapping::kId;
  if (mapping_choice_ == 1) return Mapping::kColor;
  if (mapping_choice_ == 2) return Mapping::kDepth;
  if (mapping_choice_ == 3) return Mapping::kId;
  // Object ids often travel as floats; their port says what they are.
  std::string port = evaluated_output_ ? evaluated_output_->port : "";
  if (port == "id" || port == "ids" || port.ends_with("_id") || port.ends_with("_ids")) {
    return Mapping::kId;
  }
  return is_single_channel_float(image.format) ? Mapping::kDepth : Mapping::kColor;
}

void Viewer::take_finished() {
  std::optional<EvalFinished> done = worker_->take_finished();
  if (!done) return;
  ++finished_count_;
  Wanted wanted;
  if (auto asked = in_flight_.find(done->tag); asked != in_flight_.end()) {
    wanted = asked->second;
    // Everything asked before this one was superseded (the worker keeps only the newest).
    in_flight_.erase(in_flight_.begin(), std::next(asked));
  }
  last_ms_ = done->ms;
  timings_ = std::move(done->timings);
  run_counts_ = std::move(done->run_counts);
  if (!done->error.empty()) {
    // The last good image stays on screen with the error over it.
    error_ = done->error;
    error_node_ = node_named_in(error_);
    return;
  }
  error_.clear();
  error_node_.clear();
  shown_texture_.reset(done->texture);
  image_ = done->image;
  stats_stale_ = true;  // a new picture: its histogram is read again when shown
  has_image_ = true;
  shown_frame_ = wanted.frame;
  evaluated_output_ = wanted.output;
  showing_draft_ = wanted.draft;
  if (!wanted.draft) last_full_ms_ = done->ms;
  if (wanted.quality == "preview") last_preview_ms_ = done->ms;
  display_stale_ = true;
  if (range_from_image_) measure_range();
}

void Viewer::update(const EditorState& state, bool force) {
  comparing_ = compare_ && state.compare.has_value();
  if (comparing_) {
    compare_->fixed_output_ = state.compare;
    compare_->preview_divisor_ = preview_divisor_;
    compare_->update(state, force);
  }
  take_finished();
  // Bypassed nodes are wired around by the evaluator itself (core/bypass.h).
  const Graph& graph = state.doc.graph();
  std::optional<PortRef> output = fixed_output_ ? fixed_output_ : state.shown_output();
  if (!output) {
    shown_texture_.reset();
    has_image_ = false;
    requested_.reset();
    evaluated_output_.reset();
    error_ = graph.nodes.empty() ? "" : "nothing to view: click an output port";
    error_node_.clear();
    settled_ = !worker_->busy();
    return;
  }
  DraftInputs draft_inputs;
  draft_inputs.gesture = state.doc.in_gesture();
  draft_inputs.playing = state.playing;
  draft_inputs.fps = graph.settings.fps;
  draft_inputs.last_full_ms = last_full_ms_;
  draft_inputs.graph_is_draft = graph.settings.quality == "draft";
  draft_inputs.gesture_budget_ms = gesture_budget_ms_;
  draft_inputs.graph_quality = graph.settings.quality;
  draft_inputs.last_preview_ms = last_preview_ms_;
  Wanted wanted;
  wanted.key = evaluation_key(graph, output);
  wanted.frame = state.frame;
  wanted.divisor = preview_divisor_;
  wanted.quality = proxy_quality(draft_inputs);
  wanted.draft = !wanted.quality.empty();
  wanted.output = output;
  const bool ask = force || !requested_ || !(*requested_ == wanted);
  settled_ = !ask && !worker_->busy();
  if (!ask) return;

  EvalRequest request;
  request.graph = graph;  // a copy: edits go on in the document while the worker runs
  request.output = output;
  request.options.frame = state.frame;
  request.options.retain_outputs = true;
  request.options.measure_gpu_time = true;
  request.options.finish_each_node = true;  // per-node times on the canvas must be each node's own
  if (preview_divisor_ > 1 || wanted.draft) {
    Settings& settings = request.graph.settings;
    settings.width = std::max(1, settings.width / preview_divisor_);
    settings.height = std::max(1, settings.height / preview_divisor_);
    if (wanted.draft) settings.quality = wanted.quality;  // the preset's render scale shrinks it
  }
  request.tag = next_tag_++;
  in_flight_[request.tag] = wanted;
  requested_ = wanted;
  worker_->submit(std::move(request));
  take_finished();  // an inline worker has it already
}

void Viewer::measure_range() {
  if (!has_image_ || !is_single_channel_float(image_.format)) return;
  const aq_image& image = image_;
  std::vector<float> values(static_cast<size_t>(image.width) * image.height);
  GLenum format = image.format == AQ_FORMAT_DEPTH32F ? GL_DEPTH_COMPONENT : GL_RED;
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(image.texture, 0, format, GL_FLOAT,
                    static_cast<GLsizei>(values.size() * sizeof(float)), values.data());
  std::vector<float> finite;
  finite.reserve(values.size());
  for (float v : values) {
    if (std::isfinite(v)) finite.push_back(v);
  }
  float lo = 0;
  float hi = 1;
  if (!finite.empty()) {
    auto [min_it, max_it] = std::minmax_element(finite.begin(), finite.end());
    lo = *min_it;
    hi = *max_it;
    // Background (nothing drawn) holds one value, the far plane or a cleared 1.0, over much of
    // the image; spreading the range to it would leave the scene one flat shade. Map the
    // scene's own range and let the background fall to black.
    size_t at_max = static_cast<size_t>(std::count(finite.begin(), finite.end(), hi));
    if (at_max > finite.size() / 100 && at_max < finite.size()) {
      float below = lo;
      for (float v : finite) {
        if (v < hi) below = std::max(below, v);
      }
      hi = below;
    }
  }
  range_[0] = lo;
  range_[1] = hi > lo ? hi : lo + 1.0f;
}

bool Viewer::ensure_program() {
  if (program_) return true;
  std::string log;
  GLuint vs = compile(GL_VERTEX_SHADER, kVertexShader, &log);
  GLuint fs = compile(GL_FRAGMENT_SHADER, kFragmentShader, &log);
  if (vs == 0 || fs == 0) {
    error_ = "viewer display shader: " + log;
    return false;
  }
  GLuint program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint linked = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &linked);
  if (!linked) {
    glDeleteProgram(program);
    error_ = "viewer display shader failed to link";
    return false;
  }
  program_.reset(program);
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  vertex_array_.reset(vao);
  GLuint fbo = 0;
  glCreateFramebuffers(1, &fbo);
  framebuffer_.reset(fbo);
  return true;
}

void Viewer::render_display_texture() {
  if (!has_image_ || !ensure_program()) return;
  const aq_image& image = image_;
  if (!display_ || display_width_ != image.width || display_height_ != image.height) {
    GLuint texture = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, 1, GL_RGBA8, image.width, image.height);
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    // Nearest when magnified so 1:1 and closer show real pixels.
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    display_.reset(texture);
    display_width_ = image.width;
    display_height_ = image.height;
    glNamedFramebufferTexture(framebuffer_.get(), GL_COLOR_ATTACHMENT0, texture, 0);
  }
  Mapping mapping = current_mapping();
  GLint viewport[4];
  glGetIntegerv(GL_VIEWPORT, viewport);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
  glViewport(0, 0, image.width, image.height);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_SCISSOR_TEST);
  glUseProgram(program_.get());
  glUniform1i(glGetUniformLocation(program_.get(), "u_image"), 0);
  glUniform1i(glGetUniformLocation(program_.get(), "u_ids"), 1);
  int mode = static_cast<int>(mapping);
  if (mapping == Mapping::kId && !is_integer(image.format)) mode = 3;
  glUniform1i(glGetUniformLocation(program_.get(), "u_mapping"), mode);
  glUniform1i(glGetUniformLocation(program_.get(), "u_channel"), channel_);
  glUniform1i(glGetUniformLocation(program_.get(), "u_srgb"), srgb_ ? 1 : 0);
  glUniform1f(glGetUniformLocation(program_.get(), "u_gain"), std::exp2(exposure_));
  glUniform2f(glGetUniformLocation(program_.get(), "u_range"), range_[0], range_[1]);
  glBindTextureUnit(mapping == Mapping::kId && is_integer(image.format) ? 1 : 0, image.texture);
  if (image.format == AQ_FORMAT_DEPTH32F) {
    glTextureParameteri(image.texture, GL_TEXTURE_COMPARE_MODE, GL_NONE);
  }
  glBindVertexArray(vertex_array_.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glBindTextureUnit(0, 0);
  glBindTextureUnit(1, 0);
  glUseProgram(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  display_stale_ = false;
}

void Viewer::draw_progress(ImVec2 at, float width) const {
  const double running = worker_->running_seconds();
  if (!worker_->busy()) return;
  // Expected length: the last evaluation's; the bar stops short of the end until it is done.
  const double expected = std::max(last_ms_, 1.0) / 1000.0;
  const float fraction = static_cast<float>(std::min(running / expected, 0.95));
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRectFilled(at, ImVec2(at.x + width, at.y + 6.0f), IM_COL32(0, 0, 0, 160));
  draw->AddRectFilled(at, ImVec2(at.x + width * fraction, at.y + 6.0f),
                      IM_COL32(120, 200, 255, 230));
  char label[64];
  std::snprintf(label, sizeof label, "evaluating %.1f s", running);
  ImVec2 size = ImGui::CalcTextSize(label);
  ImVec2 text(at.x + width - size.x - 8.0f, at.y - size.y - 4.0f);
  draw->AddRectFilled(ImVec2(text.x - 4, text.y - 2),
                      ImVec2(text.x + size.x + 4, text.y + size.y + 2), IM_COL32(0, 0, 0, 170));
  draw->AddText(text, IM_COL32(200, 230, 255, 255), label);
}

void Viewer::hold_for_wipe() {
  if (!display_) return;
  GLuint copy = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &copy);
  glTextureStorage2D(copy, 1, GL_RGBA8, display_width_, display_height_);
  glTextureParameteri(copy, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(copy, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(copy, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(copy, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glCopyImageSubData(display_.get(), GL_TEXTURE_2D, 0, 0, 0, 0, copy, GL_TEXTURE_2D, 0, 0, 0, 0,
                     display_width_, display_height_, 1);
  held_.reset(copy);
  held_width_ = display_width_;
  held_height_ = display_height_;
  wipe_ = true;
}

unsigned Viewer::compare_display_texture() {
  if (!comparing_ || !compare_->has_image_) return 0;
  Viewer& b = *compare_;
  if (b.srgb_ != srgb_ || b.channel_ != channel_ || b.exposure_ != exposure_ ||
      b.mapping_choice_ != mapping_choice_) {
    b.srgb_ = srgb_;
    b.channel_ = channel_;
    b.exposure_ = exposure_;
    b.mapping_choice_ = mapping_choice_;
    b.display_stale_ = true;
  }
  if (b.display_stale_) b.render_display_texture();
  return b.display_ ? b.display_.get() : 0;
}

void Viewer::draw(EditorState& state) {
  draw_toolbar(state);
  if (!error_.empty() && !has_image_) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.4f, 1.0f));
    ImGui::TextWrapped("%s", error_.c_str());
    ImGui::PopStyleColor();
  }
  if (!has_image_) {
    draw_progress(ImGui::GetCursorScreenPos(), ImGui::GetContentRegionAvail().x);
    return;
  }
  if (display_stale_) render_display_texture();
  if (!display_) return;
  histogram_plotted_ = false;
  if (show_histogram_) draw_histogram();

  draw_image_area(state);
}

void Viewer::draw_toolbar(EditorState& state) {
  // Toolbar.
  auto shown = state.shown_output();
  ImGui::TextUnformatted(shown ? shown->str().c_str() : "(no output)");
  ImGui::SameLine();
  if (ImGui::SmallButton("<")) actions::cycle_output(state, -1);
  ImGui::SameLine();
  if (ImGui::SmallButton(">")) actions::cycle_output(state, +1);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("next output (key: C, Shift+C back)");
  ImGui::SameLine();
  const char* scales[] = {"full", "1/2", "1/4"};
  int scale_index = preview_divisor_ == 4 ? 2 : preview_divisor_ == 2 ? 1 : 0;
  ImGui::SetNextItemWidth(60);
  if (ImGui::Combo("##preview", &scale_index, scales, 3)) {
    preview_divisor_ = 1 << scale_index;  // the next update asks for the new size
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("evaluation resolution (preview while editing)");
  ImGui::SameLine();
  if (ImGui::RadioButton("fit", view_.fit)) view_.fit = true;
  ImGui::SameLine();
  if (ImGui::RadioButton("1:1", !view_.fit && view_.zoom == 1.0f)) {
    ImVec2 area = ImGui::GetContentRegionAvail();
    view_.zoom_to(area.x * 0.5f, area.y * 0.5f, 1.0f);
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("wheel: zoom at the cursor; middle/right drag: pan");
  ImGui::SameLine();
  if (ImGui::SmallButton("hold A")) hold_for_wipe();
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip("keep the picture shown now as A, to compare with what follows (wipe)");
  }
  if (held_ && !comparing_) {
    ImGui::SameLine();
    ImGui::Checkbox("wipe A|B", &wipe_);
  }
  if (compare_) draw_compare_menu(state);
  if (has_image_) {
    const aq_image& image = image_;
    ImGui::SameLine();
    ImGui::TextDisabled("%dx%d %s  %.1f ms", image.width, image.height, format_name(image.format),
                        last_ms_);
    const char* mappings[] = {"auto", "colour", "depth", "id"};
    ImGui::SetNextItemWidth(80);
    if (ImGui::Combo("##mapping", &mapping_choice_, mappings, 4)) display_stale_ = true;
    if (ImGui::IsItemHovered()) {
      ImGui::SetTooltip(
          "auto: colour for RGBA, depth for one channel, id for integer textures "
          "and outputs named *id*");
    }
    ImGui::SameLine();
    Mapping mapping = current_mapping();
    if (mapping == Mapping::kId) {
      ImGui::TextDisabled("object ids: one colour per id, 0 black");
    } else if (mapping == Mapping::kDepth) {
      ImGui::SetNextItemWidth(220);
      if (ImGui::DragFloatRange2("depth range", &range_[0], &range_[1], 0.01f)) {
        range_from_image_ = false;
        display_stale_ = true;
      }
      ImGui::SameLine();
      if (ImGui::SmallButton("auto")) {
        range_from_image_ = true;
        measure_range();
        display_stale_ = true;
      }
    } else {
      const char* channels[] = {"rgb", "r", "g", "b", "a"};
      ImGui::SetNextItemWidth(70);
      if (ImGui::Combo("##channel", &channel_, channels, 5)) display_stale_ = true;
      ImGui::SameLine();
      ImGui::SetNextItemWidth(120);
      if (ImGui::SliderFloat("exposure", &exposure_, -8.0f, 8.0f, "%.1f")) display_stale_ = true;
      ImGui::SameLine();
      if (ImGui::Checkbox("sRGB", &srgb_)) display_stale_ = true;
    }
    ImGui::SameLine();
    if (ImGui::Checkbox("histogram", &show_histogram_)) stats_stale_ = true;
    note_item("viewer:histogram");
  }
}

// B of the A/B compare: any output of the graph, evaluated beside A.
void Viewer::draw_compare_menu(EditorState& state) {
  // B of the A/B compare: any output of the graph, evaluated beside A.
  ImGui::SameLine();
  const std::string current = state.compare ? "B: " + state.compare->str() : "compare with...";
  ImGui::SetNextItemWidth(150);
  if (ImGui::BeginCombo("##compare", current.c_str())) {
    if (ImGui::Selectable("(no compare)", !state.compare)) {
      (void)actions::compare_with(state, std::nullopt);
    }
    for (const auto& [id, node] : state.doc.graph().nodes) {
      const NodeType* type = state.doc.registry().find(node.type);
      if (type == nullptr) continue;
      for (const auto& port : type->outputs) {
        const PortRef ref{id, port.name};
        if (ImGui::Selectable(ref.str().c_str(), state.compare == ref)) {
          (void)actions::compare_with(state, ref);
        }
      }
    }
    ImGui::EndCombo();
  }
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip(
        "A/B wipe: the viewed output (A) left of the line, this one (B) right; "
        "shift+click an output port to pick it");
  }
}

// The picture (or the A/B wipe), its error and progress, with zoom and pan.
void Viewer::draw_image_area(EditorState& state) {
  (void)state;
  const aq_image& image = image_;
  ImVec2 avail = ImGui::GetContentRegionAvail();
  avail.y -= ImGui::GetTextLineHeightWithSpacing();  // the probe line below
  ImGui::BeginChild("##viewer_image", ImVec2(0, avail.y), false,
                    ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse);
  const ImVec2 area_at = ImGui::GetCursorScreenPos();
  const ImVec2 area(std::max(ImGui::GetContentRegionAvail().x, 1.0f),
                    std::max(ImGui::GetContentRegionAvail().y, 1.0f));
  ImGui::InvisibleButton("##image_area", area,
                         ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonMiddle |
                             ImGuiButtonFlags_MouseButtonRight);
  bool hovered = ImGui::IsItemHovered();
  const bool active = ImGui::IsItemActive();
  ImGuiIO& io = ImGui::GetIO();
  view_.place(static_cast<float>(image.width), static_cast<float>(image.height), area.x, area.y);
  if (hovered && io.MouseWheel != 0.0f) {
    view_.zoom_to(io.MousePos.x - area_at.x, io.MousePos.y - area_at.y,
                  view_.zoom * std::pow(1.2f, io.MouseWheel));
  }
  if (active && (ImGui::IsMouseDragging(ImGuiMouseButton_Middle, 2.0f) ||
                 ImGui::IsMouseDragging(ImGuiMouseButton_Right, 2.0f))) {
    view_.pan_by(io.MouseDelta.x, io.MouseDelta.y);
  }
  const float scale = view_.zoom;
  const ImVec2 top_left(area_at.x + view_.pan_x, area_at.y + view_.pan_y);
  const ImVec2 bottom_right(top_left.x + image.width * scale, top_left.y + image.height * scale);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->PushClipRect(area_at, ImVec2(area_at.x + area.x, area_at.y + area.y), true);
  auto texture_id = [](const gl::Texture& texture) {
    return reinterpret_cast<ImTextureID>(static_cast<intptr_t>(texture.get()));
  };
  // The display texture has row 0 at the bottom: flip v.
  const unsigned compared = compare_display_texture();
  float split_x = 1e30f;  // where the wipe line is on screen, when there is one
  if ((wipe_ && held_) || compared != 0) {
    const float split = top_left.x + (bottom_right.x - top_left.x) * wipe_at_;
    split_x = split;
    // Two outputs: A (viewed) left, B right. Held picture: the held A left, the live image right.
    const ImTextureID left = compared != 0 ? texture_id(display_) : texture_id(held_);
    const ImTextureID right = compared != 0
                                  ? reinterpret_cast<ImTextureID>(static_cast<intptr_t>(compared))
                                  : texture_id(display_);
    draw->AddImage(left, top_left, ImVec2(split, bottom_right.y), ImVec2(0, 1),
                   ImVec2(wipe_at_, 0));
    draw->AddImage(right, ImVec2(split, top_left.y), bottom_right, ImVec2(wipe_at_, 1),
                   ImVec2(1, 0));
    draw->AddLine(ImVec2(split, area_at.y), ImVec2(split, area_at.y + area.y),
                  IM_COL32(255, 255, 255, 220), 2.0f);
    draw->AddText(ImVec2(split - 16, area_at.y + 4), IM_COL32(255, 255, 255, 255), "A");
    draw->AddText(ImVec2(split + 6, area_at.y + 4), IM_COL32(255, 255, 255, 255), "B");
    // Drag the line with the left button.
    if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left) &&
        std::fabs(io.MousePos.x - split) < 8.0f) {
      wipe_drag_ = true;
    }
    if (wipe_drag_ && ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
      wipe_at_ = std::clamp(
          (io.MousePos.x - top_left.x) / std::max(bottom_right.x - top_left.x, 1.0f), 0.0f, 1.0f);
    } else {
      wipe_drag_ = false;
    }
  } else {
    draw->AddImage(texture_id(display_), top_left, bottom_right, ImVec2(0, 1), ImVec2(1, 0));
  }
  draw->PopClipRect();
  {
    // The error of the last evaluation over the last good image, and the progress of the
    // running one: the picture never goes blank while the graph is broken or busy.
    const ImVec2 origin = ImGui::GetWindowPos();
    const float width = ImGui::GetWindowWidth();
    std::string shown_error = error_;
    if (comparing_ && !compare_->error_.empty()) {
      shown_error += (shown_error.empty() ? "B: " : "\nB: ") + compare_->error_;
    }
    if (!shown_error.empty()) {
      ImDrawList* draw = ImGui::GetWindowDrawList();
      const float wrap = width - 16.0f;
      ImVec2 text = ImGui::CalcTextSize(shown_error.c_str(), nullptr, false, wrap);
      draw->AddRectFilled(origin, ImVec2(origin.x + width, origin.y + text.y + 12.0f),
                          IM_COL32(60, 10, 10, 220));
      draw->AddText(nullptr, 0.0f, ImVec2(origin.x + 8.0f, origin.y + 6.0f),
                    IM_COL32(255, 140, 130, 255), shown_error.c_str(), nullptr, wrap);
    }
    draw_progress(ImVec2(origin.x, origin.y + ImGui::GetWindowHeight() - 6.0f), width);
  }
  ImGui::EndChild();

  draw_probe(hovered, area_at, compared, split_x);
}

// The raw value under the cursor (B's right of the wipe line).
void Viewer::draw_probe(bool hovered, ImVec2 area_at, unsigned compared, float split_x) {
  if (hovered) {
    ImVec2 mouse = ImGui::GetMousePos();
    float px = 0;
    float py = 0;
    view_.pixel_at(mouse.x - area_at.x, mouse.y - area_at.y, &px, &py);
    // Right of the A/B wipe line the probe reads B (scaled if its size differs from A's).
    const bool probe_b = compared != 0 && mouse.x > split_x;
    const aq_image& probed = probe_b ? compare_->image_ : image_;
    if (probe_b) {
      px *= static_cast<float>(probed.width) / std::max(image_.width, 1);
      py *= static_cast<float>(probed.height) / std::max(image_.height, 1);
    }
    int x = static_cast<int>(px);
    int y = probed.height - 1 - static_cast<int>(py);
    if (x >= 0 && y >= 0 && x < probed.width && y < probed.height) {
      char line[160];
      if (compared != 0) ImGui::TextUnformatted(probe_b ? "B" : "A");
      if (compared != 0) ImGui::SameLine();
      if (probed.format == AQ_FORMAT_R32UI) {
        GLuint id = 0;
        glGetTextureSubImage(probed.texture, 0, x, y, 0, 1, 1, 1, GL_RED_INTEGER, GL_UNSIGNED_INT,
                             sizeof id, &id);
        std::snprintf(line, sizeof line, "(%d, %d)  id %u", x, y, id);
      } else if (probed.format == AQ_FORMAT_RGBA32UI) {
        GLuint words[4] = {};
        glGetTextureSubImage(probed.texture, 0, x, y, 0, 1, 1, 1, GL_RGBA_INTEGER, GL_UNSIGNED_INT,
                             sizeof words, words);
        std::snprintf(line, sizeof line, "(%d, %d)  words %08x %08x %08x %08x", x, y, words[0],
                      words[1], words[2], words[3]);
      } else if (is_single_channel_float(probed.format)) {
        float v = 0;
        GLenum format = probed.format == AQ_FORMAT_DEPTH32F ? GL_DEPTH_COMPONENT : GL_RED;
        glGetTextureSubImage(probed.texture, 0, x, y, 0, 1, 1, 1, format, GL_FLOAT, sizeof v, &v);
        std::snprintf(line, sizeof line, "(%d, %d)  %.6g", x, y, v);
      } else {
        float v[4] = {0, 0, 0, 0};
        glGetTextureSubImage(probed.texture, 0, x, y, 0, 1, 1, 1, GL_RGBA, GL_FLOAT, sizeof v, v);
        std::snprintf(line, sizeof line, "(%d, %d)  r %.4f  g %.4f  b %.4f  a %.4f", x, y, v[0],
                      v[1], v[2], v[3]);
      }
      ImGui::TextUnformatted(line);
      return;
    }
  }
  ImGui::TextDisabled("hover the image for pixel values (row 0 is the bottom)");
}

// Min, max and the spread of the viewed image's values (colour: luminance), read back once per
// new image while shown.
void Viewer::draw_histogram() {
  if (stats_stale_ || stats_image_ != image_.texture) {
    stats_stale_ = false;
    stats_image_ = image_.texture;
    const int channels = is_single_channel_float(image_.format) ? 1 : 4;
    const bool integer = image_.format == AQ_FORMAT_R32UI || image_.format == AQ_FORMAT_RGBA32UI;
    std::vector<float> pixels(static_cast<size_t>(image_.width) * image_.height * channels);
    if (!integer && !pixels.empty()) {
      const GLenum format =
          channels == 1 ? (image_.format == AQ_FORMAT_DEPTH32F ? GL_DEPTH_COMPONENT : GL_RED)
                        : GL_RGBA;
      glPixelStorei(GL_PACK_ALIGNMENT, 1);
      glGetTextureImage(image_.texture, 0, format, GL_FLOAT,
                        static_cast<GLsizei>(pixels.size() * sizeof(float)), pixels.data());
      stats_ = image_stats(pixels, channels);
    } else {
      stats_ = ImageStats{};
    }
  }
  if (stats_.counted == 0) {
    ImGui::TextDisabled("histogram: no finite values (or an integer image)");
    return;
  }
  char label[96];
  std::snprintf(label, sizeof label, "min %.4g  max %.4g", stats_.min, stats_.max);
  ImGui::PlotHistogram("##histogram", stats_.bins.data(), static_cast<int>(stats_.bins.size()), 0,
                       label, 0.0f, FLT_MAX, ImVec2(ImGui::GetContentRegionAvail().x, 48.0f));
  histogram_plotted_ = true;
}

}  // namespace aq::editor
