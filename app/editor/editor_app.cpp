// The editor window and its frame loop. See editor_app.h.
#include "editor_app.h"

#include "canvas_gestures.h"
#include "editor_actions.h"
#include "item_rects.h"
#include "param_widgets.h"
#include "script.h"

#include <aquarelle/core/image.h>
#include <aquarelle/core/image_io.h>
#include <aquarelle/core/write_guard.h>
#include <glad/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <imgui_internal.h>  // the tooltip windows, for what the scripted mode checks

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <system_error>
#include <vector>

namespace aq::editor {

namespace fs = std::filesystem;

namespace {

// The command line's exit status for a problem of the machine (no display, no GL 4.5), as
// every command uses it: 0 ok, 1 bad input, 2 environment.
constexpr int kExitEnvironment = 2;
constexpr double kHotReloadPollSeconds = 1.0;
constexpr int kFramesBeforeScreenshot = 3;  // ImGui settles its layout over a couple of frames

void* gl_proc(const char* name) {
  return reinterpret_cast<void*>(glfwGetProcAddress(name));
}

// Key presses as GLFW reports them, in order, with the modifiers of the moment: ImGui 1.86 only
// sees whether a key is down when a frame starts, so a chord pressed and released in between
// (a fast ctrl+shift+s) would be lost.
std::vector<KeyChord>& key_queue() {
  static std::vector<KeyChord> queue;
  return queue;
}

void on_key(GLFWwindow*, int key, int, int action, int mods) {
  if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
  key_queue().push_back({key, (mods & GLFW_MOD_CONTROL) != 0, (mods & GLFW_MOD_SHIFT) != 0,
                         (mods & GLFW_MOD_ALT) != 0});
}

// Left presses as GLFW reports them (time, place), for the canvas: a UI frame sees only where
// the mouse is when it starts (mouse_press.h).
struct RawPress {
  double time;
  float x;
  float y;
};
std::vector<RawPress>& press_queue() {
  static std::vector<RawPress> queue;
  return queue;
}

void on_mouse_button(GLFWwindow* window, int button, int action, int) {
  if (button != GLFW_MOUSE_BUTTON_LEFT || action != GLFW_PRESS) return;
  double x = 0;
  double y = 0;
  glfwGetCursorPos(window, &x, &y);
  press_queue().push_back({glfwGetTime(), static_cast<float>(x), static_cast<float>(y)});
}

// Files dropped on the window, taken by the next frame.
std::vector<std::string>& drop_queue() {
  static std::vector<std::string> queue;
  return queue;
}

void on_drop(GLFWwindow*, int count, const char** paths) {
  for (int i = 0; i < count; ++i) drop_queue().emplace_back(paths[i]);
}

// "ctrl+shift+s" → the chord; nullopt for a name it does not know.
std::optional<KeyChord> parse_chord(const std::string& text) {
  KeyChord chord;
  std::string rest = text;
  for (;;) {
    size_t plus = rest.find('+');
    if (plus == std::string::npos || plus + 1 == rest.size()) break;
    std::string modifier = rest.substr(0, plus);
    if (modifier == "ctrl")
      chord.ctrl = true;
    else if (modifier == "shift")
      chord.shift = true;
    else if (modifier == "alt")
      chord.alt = true;
    else
      return std::nullopt;
    rest = rest.substr(plus + 1);
  }
  static const std::map<std::string, int> kNamed = {{"tab", GLFW_KEY_TAB},
                                                    {"delete", GLFW_KEY_DELETE},
                                                    {"space", GLFW_KEY_SPACE},
                                                    {"f2", GLFW_KEY_F2},
                                                    {"f5", GLFW_KEY_F5},
                                                    {"escape", GLFW_KEY_ESCAPE},
                                                    {"backspace", GLFW_KEY_BACKSPACE}};
  if (auto named = kNamed.find(rest); named != kNamed.end()) {
    chord.key = named->second;
  } else if (rest.size() == 1 && std::isalnum(static_cast<unsigned char>(rest[0]))) {
    chord.key = std::toupper(static_cast<unsigned char>(rest[0]));  // GLFW_KEY_A == 'A'
  } else {
    return std::nullopt;
  }
  return chord;
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
    : registry_(registry),
      options_(std::move(options)),
      document_(registry),
      state_(document_),
      // Scripts and tests never touch the user's list.
      recent_(options_.script.empty() && !options_.quit ? default_recent_store() : "") {}

EditorApp::~EditorApp() {
  viewer_.reset();  // joins the evaluation thread; GL objects go while the contexts exist
  if (worker_window_ != nullptr) glfwDestroyWindow(worker_window_);
  if (compare_window_ != nullptr) glfwDestroyWindow(compare_window_);
  if (window_ != nullptr) {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window_);
  }
  glfwTerminate();
}

Status EditorApp::create_window() {
  // Without a display GLFW's own report would be a second line: it goes into the one message.
  glfwSetErrorCallback(nullptr);
  if (!glfwInit()) {
    const char* why = nullptr;
    glfwGetError(&why);
    return make_error(std::string("no display to open the editor window on (") +
                      (why != nullptr ? why : "GLFW could not start") +
                      "): run it in a desktop session, or as `xvfb-run -a aquarelle edit ...`");
  }
  glfwSetErrorCallback([](int code, const char* message) {
    std::fprintf(stderr, "aquarelle edit: GLFW error %d: %s\n", code, message);
  });
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
  load_canvas_fonts();
  glfwSetKeyCallback(window_, &on_key);  // ImGui's backend chains to these
  glfwSetMouseButtonCallback(window_, &on_mouse_button);
  glfwSetDropCallback(window_, &on_drop);
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  ImGui_ImplOpenGL3_Init("#version 450 core");
  // The evaluation thread's context: an invisible window's, sharing textures with this one.
  glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
  worker_window_ = glfwCreateWindow(16, 16, "aquarelle evaluation", nullptr, window_);
  glfwDefaultWindowHints();
  glfwMakeContextCurrent(window_);
  GLFWwindow* shared = worker_window_;
  auto worker = std::make_unique<EvalWorker>(
      registry_,
      [shared] {
        if (shared == nullptr) return false;
        glfwMakeContextCurrent(shared);
        return glfwGetCurrentContext() == shared;
      },
      [] { glfwMakeContextCurrent(nullptr); }, &gl_proc);
  viewer_ = std::make_unique<Viewer>(std::move(worker));
  // B of the A/B compare evaluates on a second worker, with a context of its own.
  glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
  compare_window_ = glfwCreateWindow(16, 16, "aquarelle compare", nullptr, window_);
  glfwDefaultWindowHints();
  glfwMakeContextCurrent(window_);
  if (compare_window_ != nullptr) {
    GLFWwindow* compare_shared = compare_window_;
    viewer_->set_compare_viewer(std::make_unique<Viewer>(std::make_unique<EvalWorker>(
        registry_,
        [compare_shared] {
          glfwMakeContextCurrent(compare_shared);
          return glfwGetCurrentContext() == compare_shared;
        },
        [] { glfwMakeContextCurrent(nullptr); }, &gl_proc)));
  }
  return Ok{};
}

void EditorApp::load_canvas_fonts() {
  ImGuiIO& io = ImGui::GetIO();
  io.Fonts->AddFontDefault();  // the UI's font stays ImGui's own
  const char* kFontFile = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";  // fonts-dejavu-core
  std::error_code error;
  const bool have_file = fs::exists(kFontFile, error);
  std::map<float, ImFont*> fonts;
  for (float size : kTextRasterSizes) {
    ImFontConfig config;
    config.OversampleH = 2;
    config.OversampleV = 1;
    config.PixelSnapH = true;
    if (have_file) {
      fonts[size] =
          io.Fonts->AddFontFromFileTTF(kFontFile, size, &config, io.Fonts->GetGlyphRangesDefault());
    } else {
      config.SizePixels = size;  // ImGui's own font, rasterised at this size
      fonts[size] = io.Fonts->AddFontDefault(&config);
    }
  }
  canvas_.set_fonts(std::move(fonts));
}

ScriptHooks EditorApp::script_hooks() {
  ScriptHooks hooks;
  hooks.fit = [this](bool whole) { canvas_.request_fit(whole); };
  hooks.add_menu = [this](const std::string& filter) { canvas_.request_add_menu(filter); };
  hooks.key = [this](const std::string& text) -> Status {
    auto chord = parse_chord(text);
    if (!chord)
      return make_error("unknown key chord '" + text + "' (e.g. \"ctrl+shift+s\", \"tab\")");
    key_queue().push_back(*chord);  // as if pressed and released between two frames
    return Ok{};
  };
  hooks.view = [this](const nlohmann::json& action) -> Status {
    if (action.contains("backdrop")) canvas_backdrop_ = action.value("backdrop", false);
    if (action.contains("split")) {  // the splitter dragged by this many pixels
      if (!action["split"].is_number()) throw std::invalid_argument("\"split\" is pixels");
      canvas_share_ = split_after_drag(canvas_share_, action["split"].get<float>(),
                                       ImGui::GetMainViewport()->WorkSize.x);
      state_.status = "canvas " + std::to_string(static_cast<int>(canvas_share_ * 100)) + "%";
    }
    if (action.contains("wipe")) {
      if (!action["wipe"].is_number()) throw std::invalid_argument("\"wipe\" is a fraction 0..1");
      viewer_->set_wipe(action["wipe"].get<float>());
    }
    if (action.value("hold_a", false)) {
      if (!viewer_->has_image()) return make_error("nothing to hold: the viewer shows no image");
      viewer_->hold_for_wipe();
    }
    return Ok{};
  };
  hooks.set_clipboard = [](const std::string& text) { ImGui::SetClipboardText(text.c_str()); };
  hooks.get_clipboard = [] {
    const char* text = ImGui::GetClipboardText();
    return std::string(text != nullptr ? text : "");
  };
  hooks.shown_frame = [this] { return viewer_->settled() ? viewer_->shown_frame() : -1; };
  hooks.gesture = [this](const nlohmann::json& action) {
    if (auto aimed = plan_item_gesture(action)) return std::move(*aimed);
    return plan_gesture(action, canvas_.layouts(), canvas_.origin(), canvas_.size());
  };
  hooks.drop = [this](const std::vector<std::string>& paths) -> Status {
    // Exactly what GLFW calls when files are dropped on the window: the registered callback.
    GLFWdropfun registered = glfwSetDropCallback(window_, nullptr);
    glfwSetDropCallback(window_, registered);
    if (registered == nullptr) return make_error("the window has no drop callback");
    std::vector<const char*> names;
    for (const std::string& path : paths) names.push_back(path.c_str());
    registered(window_, static_cast<int>(names.size()), names.data());
    return Ok{};
  };
  hooks.expect_view = [this](const nlohmann::json& action) { return check_view(action); };
  hooks.playback_fps = [this] { return playback_rate_.fps(); };
  return hooks;
}

// The graph named on the command line (a new file when it does not exist yet), and what the
// user must know at start (failed plugins); false when the graph cannot be read.
bool EditorApp::open_initial_graph() {
  if (!options_.graph.empty()) {
    std::error_code error;
    if (fs::exists(options_.graph, error)) {
      Status opened = actions::open(state_, options_.graph);
      if (!opened) {
        std::fprintf(stderr, "aquarelle edit: %s\n", opened.message().c_str());
        return false;
      }
      for (const auto& problem : document_.problems()) {
        std::fprintf(stderr, "aquarelle edit: %s\n", format_problem(problem).c_str());
      }
    } else {
      document_.new_graph(options_.graph);  // a new file, written on the first save
    }
  }
  state_.frame = document_.graph().settings.first_frame;
  if (!options_.refused_plugins.empty()) {
    actions::report(state_,
                    make_error(std::to_string(options_.refused_plugins.size()) +
                               " plugin(s) failed to load: " + options_.refused_plugins.front() +
                               " (menu Plugins lists them)"),
                    "");
  }
  return true;
}

int EditorApp::run() {
  if (!open_initial_graph()) return 1;
  ask_recovery_ = options_.script.empty() && document_.has_recovery();

  if (Status made = create_window(); !made) {
    std::fprintf(stderr, "aquarelle edit: %s\n", made.message().c_str());
    return kExitEnvironment;  // no display or no GL 4.5: the machine, not the user's input
  }

  if (!options_.script.empty()) {
    auto read = read_script(options_.script);
    if (!read) {
      std::fprintf(stderr, "aquarelle edit: %s\n", read.message().c_str());
      return 1;
    }
    runner_ = std::make_unique<ScriptRunner>(*read);
  }
  const ScriptHooks hooks = script_hooks();

  int exit_status = 0;
  int frame_index = 0;
  int frames_since_script = -1;
  bool scripted = !options_.script.empty() || !options_.screenshot.empty() || options_.quit;
  double last_time = glfwGetTime();
  double last_frame_start = last_time;
  while (running_) {
    bool idle = !state_.playing && !scripted && pending_ == Pending::kNone &&
                !(viewer_ && viewer_->refine_pending());
    if (idle) {
      glfwWaitEventsTimeout(0.25);  // wake for autosave and hot reload polls
    } else if (const double left = 1.0 / 60.0 - (glfwGetTime() - last_frame_start);
               !scripted && left > 0.0) {
      // Busy (evaluating, playing): input is answered at once, otherwise at most 60 frames a
      // second, so a spinning UI does not take the CPU the evaluation thread needs.
      glfwWaitEventsTimeout(left);
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

    const bool evaluating = viewer_->busy();
    frame();
    track_playback(now);

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
    // The screenshot waits for the image of the last edit (evaluated on the worker).
    if (frames_since_script >= 0 && (viewer_->settled() || frames_since_script < 1)) {
      ++frames_since_script;
    }
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
    const double frame_end = glfwGetTime();
    if (frame_index > 1) frame_stats_.add((frame_end - last_frame_start) * 1000.0, evaluating);
    last_frame_start = frame_end;

    if (autosave_timer_.due(now, document_.revision(), document_.in_gesture())) {
      auto saved = document_.autosave();
      if (!saved) actions::report(state_, saved.error(), "");
      autosave_timer_.written(now, document_.revision());
    }
    if (hot_reload_ && now - last_reload_poll_ > kHotReloadPollSeconds) {
      last_reload_poll_ = now;
      poll_hot_reload();
    }
  }
  if (scripted) std::fprintf(stderr, "aquarelle edit: %s\n", frame_stats_.summary().c_str());
  if (!viewer_->error().empty() && options_.quit) {
    std::fprintf(stderr, "aquarelle edit: viewer: %s\n", viewer_->error().c_str());
  }
  return exit_status;
}

void EditorApp::track_playback(double now) {
  if (!state_.playing) {
    was_playing_ = false;
    return;
  }
  if (!was_playing_) playback_rate_.reset();
  was_playing_ = true;
  if (viewer_->settled()) playback_rate_.shown(now, viewer_->shown_frame());
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
  // The next frame once the current one is on screen: playback shows every frame.
  if (!viewer_->settled()) return;
  // When evaluation is slower than real time, show the next frame rather than skipping ahead.
  play_accumulator_ = 0;
  int next = state_.frame + 1;
  if (next > settings.last_frame) next = settings.first_frame;
  actions::set_frame(state_, next);
}

void EditorApp::update_feedback() {
  feedback_.error = viewer_->error();
  feedback_.error_node = viewer_->error_node();
  // A node that failed shows "failed", not the time of an older run.
  if (!feedback_.error_node.empty()) feedback_.timings.erase(feedback_.error_node);
  for (const auto& timing : viewer_->timings()) {
    if (timing.node == feedback_.error_node) continue;
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
  std::optional<Press> press;
  for (const RawPress& raw : press_queue()) press = press_tracker_.press(raw.time, raw.x, raw.y);
  press_queue().clear();
  play_scripted_mouse(&press);
  begin_item_frame();  // widgets are noted anew as this frame draws them
  canvas_.set_press(press);
  if (!drop_queue().empty()) {  // dropped image files become read nodes at the canvas centre
    const Vec2 centre{canvas_.origin().x + canvas_.size().x * 0.5f,
                      canvas_.origin().y + canvas_.size().y * 0.5f};
    const Vec2 at = state_.canvas.to_canvas(canvas_.origin(), centre);
    (void)actions::drop_files(state_, drop_queue(), {at.x, at.y});
    drop_queue().clear();
  }
  if (const std::string& path = document_.path();
      !path.empty() && path != recent_recorded_ && fs::exists(path)) {
    recent_.add(path);  // opened or saved under this name
    recent_recorded_ = path;
  }
  ImGui::NewFrame();
  chords_ = std::move(key_queue());
  key_queue().clear();
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
  constexpr float kSplitter = 6.0f;  // the bar between canvas and viewer, dragged to resize
  float canvas_width = std::floor((available.x - kSplitter) * canvas_share_);
  float body_height = available.y - bar_height;

  ImGui::BeginChild("##canvas", ImVec2(canvas_width, body_height), true,
                    ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse);
  if (canvas_backdrop_) {
    canvas_.set_backdrop_image(viewer_->display_texture(), viewer_->display_width(),
                               viewer_->display_height());
  } else {
    canvas_.set_backdrop_image(0, 0, 0);
  }
  canvas_.draw(state_, feedback_, chords_);
  ImGui::EndChild();
  ImGui::SameLine(0, 0);
  ImGui::InvisibleButton("##split", ImVec2(kSplitter, body_height));
  note_item("##split");
  if (ImGui::IsItemHovered() || ImGui::IsItemActive()) {
    ImGui::SetMouseCursor(ImGuiMouseCursor_ResizeEW);
  }
  if (ImGui::IsItemActive()) {
    canvas_share_ =
        split_after_drag(canvas_share_, ImGui::GetIO().MouseDelta.x, available.x - kSplitter);
  }
  ImGui::SameLine(0, 0);
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
  track_tooltips();
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

// A scripted gesture stands in for the real mouse this frame. A frame aimed at a named widget
// is placed where that widget was drawn last frame; one not drawn yet (a sub-menu opening) is
// waited for, then the gesture is refused.
void EditorApp::play_scripted_mouse(std::optional<Press>* press) {
  if (mouse_frames_.empty()) return;
  ImGuiIO& io = ImGui::GetIO();
  MouseFrame input = mouse_frames_.front();
  if (!input.item.empty()) {
    ImVec2 base = gesture_press_at_;
    if (!input.from_press) {
      const std::optional<ItemRect> rect = find_item(input.item);
      if (!rect) {
        io.MousePos = last_scripted_mouse_;  // the hand waits where it is
        io.MouseDown[0] = io.MouseDown[1] = io.MouseDown[2] = false;
        if (++unresolved_frames_ < 30) return;
        state_.status = "the widget '" + input.item + "' is not on screen";
        ++state_.refused_count;
        mouse_frames_.clear();
        unresolved_frames_ = 0;
        return;
      }
      base = ImVec2((rect->x0 + rect->x1) * 0.5f, (rect->y0 + rect->y1) * 0.5f);
      if (input.left_down) gesture_press_at_ = base;
    }
    unresolved_frames_ = 0;
    input.x += base.x;
    input.y += base.y;
  }
  io.MousePos = ImVec2(input.x, input.y);
  last_scripted_mouse_ = io.MousePos;
  io.MouseDown[0] = input.left_down;
  io.MouseDown[1] = io.MouseDown[2] = false;
  io.MouseWheel = input.wheel;
  if (input.press_after >= 0) {  // a press as it happened, on the script's own clock
    scripted_press_clock_ += input.press_after;
    *press = press_tracker_.press(scripted_press_clock_, input.press_x, input.press_y);
  }
  mouse_frames_.erase(mouse_frames_.begin());
}

// Counts, for the scripted mode's checks, the frames on which a tooltip is up, apart while a
// widget is being dragged (the value under the mouse must stay visible).
void EditorApp::track_tooltips() {
  bool tooltip = false;
  for (ImGuiWindow* window : ImGui::GetCurrentContext()->Windows) {
    if ((window->Flags & ImGuiWindowFlags_Tooltip) != 0 && window->Active) tooltip = true;
  }
  const bool dragging = ImGui::IsAnyItemActive() && ImGui::GetIO().MouseDown[0];
  if (dragging) ++view_counts_.drag_frames;
  if (tooltip) ++(dragging ? view_counts_.tooltips_dragging : view_counts_.tooltips_hovering);
}

void EditorApp::handle_shortcuts() {
  const bool typing = ImGui::GetIO().WantTextInput;
  for (const KeyChord& chord : chords_) {
    if (!chord.ctrl) {
      if (typing) continue;
      if (chord.key == GLFW_KEY_SPACE) state_.playing = !state_.playing;
      if (chord.key == GLFW_KEY_F5) {
        viewer_->clear_caches();
        viewer_->update(state_, /*force=*/true);
      }
      continue;
    }
    switch (chord.key) {
      case GLFW_KEY_Z:
        chord.shift ? (void)actions::redo(state_) : (void)actions::undo(state_);
        break;
      case GLFW_KEY_Y:
        actions::redo(state_);
        break;
      case GLFW_KEY_G:  // acts on the selection wherever the mouse is, like the Edit menu
        if (typing) break;
        chord.alt ? (void)actions::ungroup_selection(state_)
                  : (void)actions::group_selection(state_);
        break;
      case GLFW_KEY_S:
        if (chord.shift) {
          file_dialog_.open("Save graph as", document_.path());
        } else {
          save_or_save_as();
        }
        break;
      case GLFW_KEY_O:
        request(Pending::kOpen);
        break;
      case GLFW_KEY_N:
        request(Pending::kNew);
        break;
      case GLFW_KEY_Q:
        request(Pending::kQuit);
        break;
      default:
        break;
    }
  }
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
  const bool file_menu = ImGui::BeginMenu("File");
  note_item("File");
  if (file_menu) {
    if (ImGui::MenuItem("New", "Ctrl+N")) request(Pending::kNew);
    if (ImGui::MenuItem("Open...", "Ctrl+O")) request(Pending::kOpen);
    const bool recent_menu = ImGui::BeginMenu("Open Recent", !recent_.paths().empty());
    note_item("Open Recent");
    if (recent_menu) {
      for (const std::string& path : recent_.paths()) {
        const bool chosen = ImGui::MenuItem(path.c_str());
        note_item(path);
        if (chosen) open_recent(path);
      }
      ImGui::EndMenu();
    }
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
    if (ImGui::MenuItem("Copy", "Ctrl+C", false, any)) {
      std::string copied = actions::copy_selection(state_);
      if (!copied.empty()) ImGui::SetClipboardText(copied.c_str());
    }
    if (ImGui::MenuItem("Paste", "Ctrl+V")) {
      const char* text = ImGui::GetClipboardText();
      (void)actions::paste(state_, text != nullptr ? text : "", std::nullopt);
    }
    if (ImGui::MenuItem("Bypass / enable", "D", false, any)) (void)actions::toggle_bypass(state_);
    if (ImGui::MenuItem("Group / collapse", "Ctrl+G", false, any)) {
      (void)actions::group_selection(state_);
    }
    if (ImGui::MenuItem("Ungroup", "Ctrl+Alt+G", false, any)) {
      (void)actions::ungroup_selection(state_);
    }
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    if (ImGui::MenuItem("Fit graph", "F")) canvas_.request_fit();
    if (ImGui::MenuItem("Show whole graph")) canvas_.request_fit(/*whole=*/true);
    if (ImGui::MenuItem("Zoom 1:1", "1")) {
      Vec2 centre{canvas_.origin().x + canvas_.size().x * 0.5f,
                  canvas_.origin().y + canvas_.size().y * 0.5f};
      state_.canvas.zoom_to(canvas_.origin(), centre, 1.0f);
    }
    if (ImGui::MenuItem("Auto-layout", "L")) (void)actions::auto_layout(state_);
    ImGui::MenuItem("Viewer image behind nodes", nullptr, &canvas_backdrop_);
    if (ImGui::MenuItem("Next output", "C")) actions::cycle_output(state_, +1);
    if (ImGui::MenuItem("Graph output")) state_.viewed.reset();
    ImGui::Separator();
    if (ImGui::MenuItem("Shader hot reload", nullptr, &hot_reload_)) {
      viewer_->set_shader_hot_reload(hot_reload_);
      viewer_->clear_caches();
      newest_shader_ = {};
      last_reload_poll_ = 0;
      viewer_->update(state_, /*force=*/true);
    }
    if (ImGui::MenuItem("Reload shaders now", "F5")) {
      viewer_->clear_caches();
      viewer_->update(state_, /*force=*/true);
    }
    ImGui::EndMenu();
  }
  if (!options_.refused_plugins.empty() && ImGui::BeginMenu("Plugins (failed)")) {
    ImGui::TextDisabled("these plugin files could not be loaded; their nodes are missing:");
    for (const auto& refused : options_.refused_plugins) ImGui::TextUnformatted(refused.c_str());
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
  double seconds = (state_.frame - settings.first_frame) / std::max(settings.fps, 1e-3);
  const double ui_ms = frame_stats_.recent_ms();
  // The rate playback reaches beside the graph's own; the UI's redraw time without a rate
  // (an idle UI redraws on demand, its rate says nothing about playback).
  char rate[64];
  if (state_.playing || playback_rate_.fps() > 0) {
    std::snprintf(rate, sizeof rate, "%s %.1f of %g fps", state_.playing ? "playing" : "played",
                  playback_rate_.fps(), settings.fps);
  } else {
    std::snprintf(rate, sizeof rate, "%g fps", settings.fps);
  }
  char timing[200];
  std::snprintf(timing, sizeof timing, "t = %.2f s  %s  eval %.1f ms%s  UI %.1f ms", seconds, rate,
                viewer_->last_evaluation_ms(), viewer_->showing_draft() ? " (proxy)" : "", ui_ms);
  // The slider takes what the timing text leaves, so the text is never cut by the window edge.
  ImGui::SetNextItemWidth(std::max(ImGui::GetContentRegionAvail().x -
                                       ImGui::CalcTextSize(timing).x -
                                       2 * ImGui::GetStyle().ItemSpacing.x,
                                   80.0f));
  // Guarded: a graph may declare frames beyond what ImGui's slider holds (it would abort).
  if (slider_int_guarded("##frame", &frame, settings.first_frame,
                         std::max(settings.first_frame, settings.last_frame), "frame %d")) {
    actions::set_frame(state_, frame);
  }
  ImGui::SameLine();
  ImGui::TextUnformatted(timing);
  // Status line: the file, then the last action's result cut to the width left (the whole
  // text on hover), so nothing is clipped by the window edge.
  ImGui::TextDisabled("%s%s", document_.path().empty() ? "(untitled)" : document_.path().c_str(),
                      document_.dirty() ? " *" : "");
  ImGui::SameLine();
  ImVec4 colour = state_.status_is_error ? ImVec4(1, 0.45f, 0.4f, 1) : ImVec4(0.7f, 0.85f, 0.7f, 1);
  std::string status = state_.status.substr(0, state_.status.find('\n'));
  const float room = ImGui::GetContentRegionAvail().x;
  if (ImGui::CalcTextSize(status.c_str()).x > room) {
    while (!status.empty() && ImGui::CalcTextSize((status + "...").c_str()).x > room) {
      status.pop_back();
    }
    status += "...";
  }
  ImGui::TextColored(colour, "%s", status.c_str());
  if (ImGui::IsItemHovered() && status != state_.status) {
    ImGui::SetTooltip("%s", state_.status.c_str());
  }
}

void EditorApp::request(Pending pending) {
  if (document_.dirty() && !options_.quit) {
    pending_ = pending;
    ask_unsaved_ = true;
    return;
  }
  perform(pending);
}

void EditorApp::open_recent(const std::string& path) {
  recent_target_ = path;
  request(Pending::kOpenRecent);
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
    case Pending::kOpenRecent:
      if (actions::open(state_, recent_target_)) canvas_.request_fit();
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

  if (ImGui::BeginPopupModal("Replace file?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::Text("%s exists already.\nReplace it with this graph?", replace_path_.c_str());
    if (ImGui::Button("Replace")) {
      ImGui::CloseCurrentPopup();
      if (actions::save_as(state_, replace_path_, /*replace=*/true) && save_as_then_continue_) {
        perform(pending_);
      }
      save_as_then_continue_ = false;
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) {
      ImGui::CloseCurrentPopup();
      actions::report(state_, Ok{}, "not saved: " + replace_path_ + " kept as it was");
      save_as_then_continue_ = false;
      pending_ = Pending::kNone;
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
    } else if (document_.would_replace(chosen)) {
      replace_path_ = chosen;  // asked below; the pending action waits for the answer
      ImGui::OpenPopup("Replace file?");
      return;
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
    viewer_->clear_caches();
    viewer_->update(state_, /*force=*/true);
    actions::report(state_, Ok{}, "shaders reloaded");
  }
}

Status EditorApp::write_screenshot(const std::string& path) {
  const std::vector<ReadFile> reads = files_read_by(document_.graph(), registry_);
  if (auto may = check_may_write("--screenshot", path, reads); !may.ok()) return may;
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
