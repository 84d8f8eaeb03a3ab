// The editor window: GLFW window with a GL 4.5 core context that the evaluator adopts, Dear
// ImGui on top, and the frame loop that lays out the menu bar, the canvas, the viewer, the
// parameter panel, the time bar and the modal prompts (unsaved changes, crash recovery).
//
//   frame: poll events ─► advance time ─► viewer.update (take the worker's finished image; ask
//          for a new one if what it depends on changed)
//          ─► ImGui: menus, canvas, viewer, parameters, time bar ─► render ─► [screenshot] ─► swap
#pragma once

#include "autosave_timer.h"
#include "canvas.h"
#include "document.h"
#include "editor_state.h"
#include "file_dialog.h"
#include "frame_stats.h"
#include "mouse_press.h"
#include "pane_split.h"
#include "param_panel.h"
#include "playback_rate.h"
#include "recent_files.h"
#include "script.h"
#include "viewer.h"

#include <aquarelle/core/gl_context.h>
#include <aquarelle/core/registry.h>
#include <aquarelle/core/result.h>

#include <imgui.h>

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

struct GLFWwindow;

namespace aq::editor {

struct EditorOptions {
  std::string graph;       // file to open (created on save when it does not exist)
  std::string script;      // actions to run after the first frame
  std::string screenshot;  // PNG of the window after the script
  bool quit = false;       // exit after the screenshot (or the script)
  int width = 1280;
  int height = 800;
  // Plugins that failed to load ("FILE: reason"): shown in the editor, not only on the terminal.
  std::vector<std::string> refused_plugins;
};

class EditorApp {
 public:
  EditorApp(const Registry& registry, EditorOptions options);
  ~EditorApp();
  EditorApp(const EditorApp&) = delete;
  EditorApp& operator=(const EditorApp&) = delete;

  // Opens the window and runs until it closes; returns the exit status.
  int run();

 private:
  enum class Pending { kNone, kQuit, kNew, kOpen, kOpenRecent };

  Status create_window();
  bool open_initial_graph();
  void frame();
  void draw_menu_bar();
  void draw_time_bar();
  void draw_modals();
  void handle_shortcuts();
  void load_canvas_fonts();
  void advance_time(double seconds);
  // Feeds the reached playback rate the graph frame on screen (every UI frame).
  void track_playback(double now);
  ScriptHooks script_hooks();
  void play_scripted_mouse(std::optional<Press>* press);
  void track_tooltips();
  // The scripted "expect_view" check (editor_view_check.cpp).
  Status check_view(const nlohmann::json& action);
  void update_feedback();
  void poll_hot_reload();
  // Runs `pending` now, or asks first when there are unsaved changes.
  void request(Pending pending);
  void perform(Pending pending);
  // File > Open Recent: opens `path` once unsaved changes are settled.
  void open_recent(const std::string& path);
  void save_or_save_as();
  void update_title();
  Status write_screenshot(const std::string& path);

  const Registry& registry_;
  EditorOptions options_;
  Document document_;
  EditorState state_;
  GLFWwindow* window_ = nullptr;
  GLFWwindow* worker_window_ = nullptr;   // invisible; its context is the evaluation thread's
  GLFWwindow* compare_window_ = nullptr;  // invisible; the A/B compare's evaluation thread's
  FrameStats frame_stats_;
  std::vector<KeyChord> chords_;  // this frame's key presses
  bool canvas_backdrop_ = false;  // View > Viewer image behind nodes
  std::unique_ptr<GlContext> context_;
  std::unique_ptr<Viewer> viewer_;
  Canvas canvas_;
  ParamPanel params_;
  FileDialog file_dialog_;
  NodeFeedback feedback_;
  std::unique_ptr<ScriptRunner> runner_;
  std::vector<MouseFrame> mouse_frames_;  // scripted input still to play, one per frame
  ImVec2 gesture_press_at_{0, 0};         // where the scripted gesture pressed its widget
  ImVec2 last_scripted_mouse_{0, 0};
  int unresolved_frames_ = 0;  // frames a gesture waited for its widget to be drawn
  struct ViewCounts {          // UI frames seen since the scripted mode last checked them
    int drag_frames = 0;
    int tooltips_dragging = 0;
    int tooltips_hovering = 0;
  } view_counts_;

  Pending pending_ = Pending::kNone;
  bool ask_unsaved_ = false;
  bool ask_recovery_ = false;
  bool save_as_then_continue_ = false;
  std::string replace_path_;  // Save As named an existing file: asking before replacing it
  bool running_ = true;
  double play_accumulator_ = 0;
  float canvas_share_ = kDefaultCanvasShare;  // of the width; the splitter moves it
  PressTracker press_tracker_;                // double-clicks from the presses' own times
  double scripted_press_clock_ = 1000.0;
  RecentFiles recent_;
  std::string recent_recorded_;
  std::string recent_target_;   // what Open Recent opens (Pending::kOpenRecent)  // the document
                                // path last added to recent_
  PlaybackRate playback_rate_;  // the frame rate playback reaches
  bool was_playing_ = false;
  AutosaveTimer autosave_timer_;  // after each completed edit, debounced
  std::string title_;

  bool hot_reload_ = false;
  double last_reload_poll_ = 0;
  std::filesystem::file_time_type newest_shader_{};
};

// The folders whose shader files the hot reload watches: <source>/plugins/*/shaders and
// <source>/nodes/shaders, where <source> is found by walking up from the executable (a build
// folder inside the source tree) or named by $AQUARELLE_SOURCE_DIR.
std::vector<std::filesystem::path> shader_source_folders();

}  // namespace aq::editor
