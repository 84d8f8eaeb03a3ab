// The editor window and its frame loop. See editor_app.h.
#include "editor_app.h"

#include "canvas_gestures.h"
#include "editor_actions.h"
#include "script.h"

#include <aquarelle/core/image.h>
#include <aquarelle/core/image_io.h>
#include <glad/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <system_error>
#include <vector>

namespace aq::editor {

namespace fs = std::filesystem;

namespace {

constexpr double kAutosaveSeconds = 30.0;
constexpr double kHotReloadPollSeconds = 1.0;
constexpr int kFramesBeforeScreenshot = 3;  // ImGui settles its layout over a couple of frames

void* gl_proc(const char* name) {
  return reinterpret_cast<void*>(glfwGetProcAddress(name));
}

bool is_shader_file(const fs::path& path) {
  std::string ext = path.extension().string();
  return ext == ".frag" || ext == ".vert" || ext == ".comp" || ext == ".geom" || ext == ".glsl";
}

}  // namespace

std::vector<fs::path> shader_source_folders() {
  std::error_code error;
  fs::path source;
  if (const char* env = std::getenv("AQUARELLE_SOURCE_DIR"); env != nullptr && *env) {
    source = env;
  } else {
    for (fs::path dir = fs::read_symlink("/proc/self/exe", error).parent_path(); !dir.empty();
         dir = dir.parent_path()) {
      if (fs::is_directory(dir / "plugins", error) &&
          fs::is_directory(dir / "nodes" / "shaders", error)) {
        source = dir;
        break;
      }
      if (dir == dir.parent_path()) break;
    }
  }
  std::vector<fs::path> folders;
  if (source.empty()) return folders;
  folders.push_back(source / "nodes" / "shaders");
  for (const auto& plugin : fs::directory_iterator(source / "plugins", error)) {
    if (fs::is_directory(plugin.path() / "shaders", error))
      folders.push_back(plugin.path() / "shaders");
  }
  return folders;
}

EditorApp::EditorApp(const Registry& registry, EditorOptions options)
    : registry_(registry), options_(std::move(options)), document_(registry), state_(document_) {}

EditorApp::~EditorApp() {
  viewer_.reset();  // GL objects go while the context still exists
  if (window_ != nullptr) {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window_);
  }
  glfwTerminate();
}

Status EditorApp::create_window() {
  glfwSetErrorCallback([](int code, const char* message) {
    std::fprintf(stderr, "aquarelle edit: GLFW error %d: %s\n", code, message);
  });
  if (!glfwInit()) {
    return make_error(
        "cannot start GLFW: is there a display? (run under a desktop session, or "
        "headless as `xvfb-run -a aquarelle edit ...`)");
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  window_ = glfwCreateWindow(options_.width, options_.height, "aquarelle", nullptr, nullptr);
  if (window_ == nullptr) {
    return make_error(
        "cannot open a window with OpenGL 4.5 core: the GL driver must offer 4.5 "
        "(Mesa 22+ does, also as llvmpipe)");
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(options_.quit ? 0 : 1);
  context_ = adopt_current_context(&gl_proc);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini dropped in the user's folder
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  ImGui_ImplOpenGL3_Init("#version 450 core");
  viewer_ = std::make_unique<Viewer>(*context_, registry_);
  return Ok{};
}

int EditorApp::run() {
  if (!options_.graph.empty()) {
    std::error_code error;
    if (fs::exists(options_.graph, error)) {
      Status opened = actions::open(state_, options_.graph);
      if (!opened) {
        std::fprintf(stderr, "aquarelle edit: %s\n", opened.message().c_str());
        return 1;
      }
      for (const auto& problem : document_.problems()) {
        std::fprintf(stderr, "aquarelle edit: %s\n", format_problem(problem).c_str());
      }
    } else {
      document_.new_graph(options_.graph);  // a new file, written on the first save
    }
  }
  state_.frame = document_.graph().settings.first_frame;
  ask_recovery_ = options_.script.empty() && document_.has_recovery();

  if (Status made = create_window(); !made) {
    std::fprintf(stderr, "aquarelle edit: %s\n", made.message().c_str());
    return 1;
  }

  if (!options_.script.empty()) {
    auto read = read_script(options_.script);
    if (!read) {
      std::fprintf(stderr, "aquarelle edit: %s\n", read.message().c_str());
      return 1;
    }
    runner_ = std::make_unique<ScriptRunner>(*read);
  }
  ScriptHooks hooks;
  hooks.fit = [this] { canvas_.request_fit(); };
  hooks.add_menu = [this](const std::string& filter) { canvas_.request_add_menu(filter); };
  hooks.gesture = [this](const nlohmann::json& action) {
    return plan_gesture(action, canvas_.layouts(), canvas_.origin(), canvas_.size());
  };

  int exit_status = 0;
  int frame_index = 0;
  int frames_since_script = -1;
  bool scripted = !options_.script.empty() || !options_.screenshot.empty() || options_.quit;
  double last_time = glfwGetTime();
  while (running_) {
    bool idle = !state_.playing && !scripted && pending_ == Pending::kNone &&
                !(viewer_ && viewer_->refine_pending());
    if (idle) {
      glfwWaitEventsTimeout(0.25);  // wake for autosave and hot reload polls
    } else {
      glfwPollEvents();
    }
    if (glfwWindowShouldClose(window_)) {
      glfwSetWindowShouldClose(window_, GLFW_FALSE);
      request(Pending::kQuit);
    }
    double now = glfwGetTime();
    advance_time(now - last_time);
    last_time = now;

    frame();

    // The script starts once the first frame has laid out the canvas, then advances a step per
    // frame so its mouse gestures play as input to the following frames.
    if (frame_index >= 1 && frames_since_script < 0) {
      Status stepped = runner_ ? runner_->step(state_, hooks, &mouse_frames_) : Status(Ok{});
      if (!stepped) {
        std::fprintf(stderr, "aquarelle edit: %s\n", stepped.message().c_str());
        exit_status = 1;
        mouse_frames_.clear();
        frames_since_script = 0;
      } else if (!runner_ || runner_->finished()) {
        frames_since_script = 0;
      }
    }
    if (frames_since_script >= 0) ++frames_since_script;
    if (frames_since_script == kFramesBeforeScreenshot) {
      if (!options_.screenshot.empty()) {
        Status shot = write_screenshot(options_.screenshot);
        if (!shot) {
          std::fprintf(stderr, "aquarelle edit: %s\n", shot.message().c_str());
          exit_status = 1;
        }
      }
      if (options_.quit) running_ = false;
    }
    glfwSwapBuffers(window_);
    ++frame_index;

    if (!scripted && now - last_autosave_ > kAutosaveSeconds) {
      last_autosave_ = now;
      auto saved = document_.autosave();
      if (!saved) actions::report(state_, saved.error(), "");
    }
    if (hot_reload_ && now - last_reload_poll_ > kHotReloadPollSeconds) {
      last_reload_poll_ = now;
      poll_hot_reload();
    }
  }
  if (!viewer_->error().empty() && options_.quit) {
    std::fprintf(stderr, "aquarelle edit: viewer: %s\n", viewer_->error().c_str());
  }
  return exit_status;
}

void EditorApp::advance_time(double seconds) {
  if (!state_.playing) {
    play_accumulator_ = 0;
    return;
  }
  const Settings& settings = document_.graph().settings;
  play_accumulator_ += seconds;
  double frame_time = 1.0 / std::max(settings.fps, 1e-3);
  if (play_accumulator_ < frame_time) return;
  // When evaluation is slower than real time, show the next frame rather than skipping ahead.
  play_accumulator_ = 0;
  int next = state_.frame + 1;
  if (next > settings.last_frame) next = settings.first_frame;
  actions::set_frame(state_, next);
}

void EditorApp::update_feedback() {
  feedback_.error = viewer_->error();
  feedback_.error_node = viewer_->error_node();
  for (const auto& timing : viewer_->timings()) {
    auto known = feedback_.timings.find(timing.node);
    if (timing.cached && known != feedback_.timings.end()) {
      known->second.cached = true;  // keep the time it took when it last ran
    } else {
      feedback_.timings[timing.node] = timing;
    }
  }
  std::erase_if(feedback_.timings,
                [&](const auto& entry) { return !document_.graph().nodes.count(entry.first); });
}

void EditorApp::frame() {
  viewer_->update(state_);
  update_feedback();
  update_title();

  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  if (!mouse_frames_.empty()) {
    // A scripted gesture stands in for the real mouse this frame.
    ImGuiIO& io = ImGui::GetIO();
    const MouseFrame& input = mouse_frames_.front();
    io.MousePos = ImVec2(input.x, input.y);
    io.MouseDown[0] = input.left_down;
    io.MouseDown[1] = io.MouseDown[2] = false;
    io.MouseWheel = input.wheel;
    mouse_frames_.erase(mouse_frames_.begin());
  }
  ImGui::NewFrame();
  handle_shortcuts();
  draw_menu_bar();

  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(viewport->WorkPos);
  ImGui::SetNextWindowSize(viewport->WorkSize);
  ImGui::PushStyleVar(ImGuiStyleVar_WindowRounding, 0.0f);
  ImGui::Begin("##main", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                   ImGuiWindowFlags_NoBringToFrontOnFocus | ImGuiWindowFlags_NoSavedSettings);
  ImGui::PopStyleVar();
  const float bar_height = ImGui::GetFrameHeightWithSpacing() * 2.0f + 4.0f;
  ImVec2 available = ImGui::GetContentRegionAvail();
  float canvas_width = std::floor(available.x * 0.56f);
  float body_height = available.y - bar_height;

  ImGui::BeginChild("##canvas", ImVec2(canvas_width, body_height), true,
                    ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse);
  canvas_.draw(state_, feedback_);
  ImGui::EndChild();
  ImGui::SameLine();
  ImGui::BeginGroup();
  ImGui::BeginChild("##viewer", ImVec2(0, std::floor(body_height * 0.58f)), true,
                    ImGuiWindowFlags_NoScrollbar);
  viewer_->draw(state_);
  ImGui::EndChild();
  ImGui::BeginChild(
      "##params",
      ImVec2(0, body_height - std::floor(body_height * 0.58f) - ImGui::GetStyle().ItemSpacing.y),
      true);
  params_.draw(state_, feedback_);
  ImGui::EndChild();
  ImGui::EndGroup();
  draw_time_bar();
  ImGui::End();

  draw_modals();
  ImGui::Render();
  int width = 0;
  int height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, width, height);
  glClearColor(0.1f, 0.1f, 0.11f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void EditorApp::handle_shortcuts() {
  ImGuiIO& io = ImGui::GetIO();
  if (io.WantTextInput || !io.KeyCtrl) {
    if (!io.WantTextInput && ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Space), false)) {
      state_.playing = !state_.playing;
    }
    if (!io.WantTextInput && ImGui::IsKeyPressed(GLFW_KEY_F5, false)) {
      viewer_->evaluator().clear();
      viewer_->update(state_, /*force=*/true);
    }
    return;
  }
  if (ImGui::IsKeyPressed(GLFW_KEY_Z)) {
    io.KeyShift ? actions::redo(state_) : actions::undo(state_);
  }
  if (ImGui::IsKeyPressed(GLFW_KEY_Y)) actions::redo(state_);
  if (ImGui::IsKeyPressed(GLFW_KEY_S, false)) {
    if (io.KeyShift) {
      file_dialog_.open("Save graph as", document_.path());
    } else {
      save_or_save_as();
    }
  }
  if (ImGui::IsKeyPressed(GLFW_KEY_O, false)) request(Pending::kOpen);
  if (ImGui::IsKeyPressed(GLFW_KEY_N, false)) request(Pending::kNew);
  if (ImGui::IsKeyPressed(GLFW_KEY_Q, false)) request(Pending::kQuit);
}

void EditorApp::save_or_save_as() {
  if (document_.path().empty()) {
    file_dialog_.open("Save graph as", "");
  } else {
    (void)actions::save(state_);
  }
}

void EditorApp::draw_menu_bar() {
  if (!ImGui::BeginMainMenuBar()) return;
  if (ImGui::BeginMenu("File")) {
    if (ImGui::MenuItem("New", "Ctrl+N")) request(Pending::kNew);
    if (ImGui::MenuItem("Open...", "Ctrl+O")) request(Pending::kOpen);
    if (ImGui::MenuItem("Save", "Ctrl+S")) save_or_save_as();
    if (ImGui::MenuItem("Save As...", "Ctrl+Shift+S")) {
      file_dialog_.open("Save graph as", document_.path());
    }
    ImGui::Separator();
    if (ImGui::MenuItem("Quit", "Ctrl+Q")) request(Pending::kQuit);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Edit")) {
    std::string undo = "Undo " + document_.undo_label();
    std::string redo = "Redo " + document_.redo_label();
    if (ImGui::MenuItem(undo.c_str(), "Ctrl+Z", false, document_.can_undo())) actions::undo(state_);
    if (ImGui::MenuItem(redo.c_str(), "Ctrl+Shift+Z", false, document_.can_redo())) {
      actions::redo(state_);
    }
    ImGui::Separator();
    if (ImGui::MenuItem("Add node...", "Tab")) canvas_.request_add_menu();
    bool any = !state_.selection.empty();
    if (ImGui::MenuItem("Duplicate", "Ctrl+D", false, any))
      (void)actions::duplicate_selection(state_);
    if (ImGui::MenuItem("Delete", "Del", false, any)) (void)actions::delete_selection(state_);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    if (ImGui::MenuItem("Fit graph", "F")) canvas_.request_fit();
    if (ImGui::MenuItem("Zoom 1:1", "1")) state_.canvas.zoom = 1.0f;
    if (ImGui::MenuItem("Next output", "C")) actions::cycle_output(state_, +1);
    if (ImGui::MenuItem("Graph output")) state_.viewed.reset();
    ImGui::Separator();
    if (ImGui::MenuItem("Shader hot reload", nullptr, &hot_reload_)) {
      viewer_->evaluator().set_shader_hot_reload(hot_reload_);
      viewer_->evaluator().clear();
      newest_shader_ = {};
      last_reload_poll_ = 0;
      viewer_->update(state_, /*force=*/true);
    }
    if (ImGui::MenuItem("Reload shaders now", "F5")) {
      viewer_->evaluator().clear();
      viewer_->update(state_, /*force=*/true);
    }
    ImGui::EndMenu();
  }
  ImGui::EndMainMenuBar();
}

void EditorApp::draw_time_bar() {
  const Settings& settings = document_.graph().settings;
  if (ImGui::Button(state_.playing ? "Pause" : "Play", ImVec2(60, 0))) {
    state_.playing = !state_.playing;
  }
  ImGui::SameLine();
  if (ImGui::ArrowButton("##previous", ImGuiDir_Left)) actions::set_frame(state_, state_.frame - 1);
  ImGui::SameLine();
  if (ImGui::ArrowButton("##next", ImGuiDir_Right)) actions::set_frame(state_, state_.frame + 1);
  ImGui::SameLine();
  int frame = state_.frame;
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x - 260);
  if (ImGui::SliderInt("##frame", &frame, settings.first_frame,
                       std::max(settings.first_frame, settings.last_frame), "frame %d")) {
    actions::set_frame(state_, frame);
  }
  ImGui::SameLine();
  double seconds = (state_.frame - settings.first_frame) / std::max(settings.fps, 1e-3);
  ImGui::Text("t = %.2f s  %.0f fps  eval %.1f ms%s", seconds, settings.fps,
              viewer_->last_evaluation_ms(),
              viewer_->refine_pending() ? " (draft while editing)" : "");
  // Status line.
  ImGui::TextDisabled("%s%s", document_.path().empty() ? "(untitled)" : document_.path().c_str(),
                      document_.dirty() ? " *" : "");
  ImGui::SameLine();
  ImVec4 colour = state_.status_is_error ? ImVec4(1, 0.45f, 0.4f, 1) : ImVec4(0.7f, 0.85f, 0.7f, 1);
  ImGui::TextColored(colour, "%s", state_.status.c_str());
}

void EditorApp::request(Pending pending) {
  if (document_.dirty() && !options_.quit) {
    pending_ = pending;
    ask_unsaved_ = true;
    return;
  }
  perform(pending);
}

void EditorApp::perform(Pending pending) {
  switch (pending) {
    case Pending::kQuit:
      running_ = false;
      break;
    case Pending::kNew:
      actions::new_graph(state_);
      canvas_.request_fit();
      break;
    case Pending::kOpen:
      file_dialog_.open("Open graph", document_.path());
      break;
    case Pending::kNone:
      break;
  }
  pending_ = Pending::kNone;
}

void EditorApp::draw_modals() {
  if (ask_unsaved_) {
    ImGui::OpenPopup("Unsaved changes");
    ask_unsaved_ = false;
  }
  if (ImGui::BeginPopupModal("Unsaved changes", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::Text("%s has unsaved changes.",
                document_.path().empty() ? "The graph" : document_.path().c_str());
    if (ImGui::Button("Save")) {
      ImGui::CloseCurrentPopup();
      if (document_.path().empty()) {
        save_as_then_continue_ = true;
        file_dialog_.open("Save graph as", "");
      } else if (actions::save(state_)) {
        perform(pending_);
      }
    }
    ImGui::SameLine();
    if (ImGui::Button("Discard changes")) {
      ImGui::CloseCurrentPopup();
      document_.discard_recovery();
      perform(pending_);
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) {
      ImGui::CloseCurrentPopup();
      pending_ = Pending::kNone;
    }
    ImGui::EndPopup();
  }

  if (ask_recovery_) {
    ImGui::OpenPopup("Recover unsaved work?");
    ask_recovery_ = false;
  }
  if (ImGui::BeginPopupModal("Recover unsaved work?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::Text("An autosave newer than the graph exists:\n%s\n(the editor may have crashed)",
                document_.autosave_path().c_str());
    if (ImGui::Button("Recover")) {
      actions::report(state_, document_.recover(), "recovered the autosave; save to keep it");
      canvas_.request_fit();
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Discard it")) {
      document_.discard_recovery();
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }

  std::string chosen;
  std::string title = file_dialog_.title();
  if (file_dialog_.draw(&chosen)) {
    if (title == "Open graph") {
      if (actions::open(state_, chosen)) {
        canvas_.request_fit();
        if (document_.has_recovery()) ask_recovery_ = true;
      }
    } else if (actions::save_as(state_, chosen) && save_as_then_continue_) {
      perform(pending_);
    }
    save_as_then_continue_ = false;
  } else if (file_dialog_.title().empty() && !title.empty()) {
    save_as_then_continue_ = false;  // cancelled
    pending_ = Pending::kNone;
  }
}

void EditorApp::update_title() {
  std::string name =
      document_.path().empty() ? "untitled" : fs::path(document_.path()).filename().string();
  std::string title = "aquarelle edit — " + name + (document_.dirty() ? " *" : "");
  if (title != title_) {
    glfwSetWindowTitle(window_, title.c_str());
    title_ = title;
  }
}

void EditorApp::poll_hot_reload() {
  fs::file_time_type newest{};
  std::error_code error;
  for (const auto& folder : shader_source_folders()) {
    for (const auto& entry : fs::directory_iterator(folder, error)) {
      if (!is_shader_file(entry.path())) continue;
      newest = std::max(newest, entry.last_write_time(error));
    }
  }
  if (newest_shader_ == fs::file_time_type{}) {
    newest_shader_ = newest;
    return;
  }
  if (newest > newest_shader_) {
    newest_shader_ = newest;
    viewer_->evaluator().clear();
    viewer_->update(state_, /*force=*/true);
    actions::report(state_, Ok{}, "shaders reloaded");
  }
}

Status EditorApp::write_screenshot(const std::string& path) {
  int width = 0;
  int height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  std::vector<unsigned char> bytes(static_cast<size_t>(width) * height * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
  // glReadPixels gives the bottom row first, as ImageF expects.
  ImageF image(width, height, 4);
  for (size_t i = 0; i < bytes.size(); ++i) image.pixels[i] = bytes[i] / 255.0f;
  for (size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 1.0f;
  Status written = write_image(path, image);
  if (!written) return make_error("screenshot: " + written.message());
  std::fprintf(stderr, "aquarelle edit: screenshot %dx%d written to %s\n", width, height,
               path.c_str());
  return Ok{};
}

}  // namespace aq::editor
