// The scripted mode's interpreter. See script.h.
#include "script.h"

#include "document.h"
#include "editor_actions.h"

#include <aquarelle/core/message_text.h>
#include <aquarelle/sdk/regular_file.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace aq::editor {

namespace {

std::string text_field(const nlohmann::json& action, const char* key) {
  auto it = action.find(key);
  if (it == action.end() || !it->is_string()) {
    throw std::invalid_argument(std::string("needs a string \"") + key + "\"");
  }
  return it->get<std::string>();
}

PortRef port_field(const nlohmann::json& action, const char* key) {
  std::string text = text_field(action, key);
  auto ref = PortRef::parse(text);
  if (!ref)
    throw std::invalid_argument(std::string("\"") + key + "\" must be \"node.port\", got '" + text +
                                "'");
  return *ref;
}

Position position_field(const nlohmann::json& action, const char* key, Position fallback) {
  auto it = action.find(key);
  if (it == action.end()) return fallback;
  if (!it->is_array() || it->size() != 2 || !(*it)[0].is_number() || !(*it)[1].is_number()) {
    throw std::invalid_argument(std::string("\"") + key + "\" must be [x, y]");
  }
  return {(*it)[0].get<float>(), (*it)[1].get<float>()};
}

std::vector<std::string> nodes_field(const nlohmann::json& action) {
  auto it = action.find("nodes");
  if (it == action.end() || !it->is_array()) throw std::invalid_argument("needs \"nodes\": [ids]");
  std::vector<std::string> ids;
  for (const auto& id : *it) {
    if (!id.is_string()) throw std::invalid_argument("\"nodes\" must hold node ids (strings)");
    ids.push_back(id.get<std::string>());
  }
  return ids;
}

// Without a window (run_script) copy and paste go through this stand-in for the clipboard.
std::string& clipboard() {
  static std::string text;
  return text;
}

Status status_of(bool done, const std::string& why) {
  return done ? Status(Ok{}) : Status(make_error(why));
}

// The actions that edit the graph or the selection; nullopt for any other kind.
std::optional<Status> run_edit_action(EditorState& state, const std::string& kind,
                                      const nlohmann::json& action) {
  if (kind == "add_node") {
    auto added =
        actions::add_node(state, text_field(action, "type"), position_field(action, "at", {0, 0}),
                          action.value("id", std::string()));
    return added ? Status(Ok{}) : Status(added.error());
  }
  if (kind == "link") {
    PortRef to = port_field(action, "to");
    return actions::link(state, port_field(action, "from"), to.node, to.port);
  }
  if (kind == "unlink") {
    PortRef to = port_field(action, "to");
    return actions::unlink(state, to.node, to.port);
  }
  if (kind == "set_param") {
    if (!action.contains("value")) throw std::invalid_argument("needs a \"value\" (null resets)");
    return actions::set_param(state, text_field(action, "node"), text_field(action, "param"),
                              action["value"]);
  }
  if (kind == "move") {
    return actions::move(state, {{text_field(action, "node"), position_field(action, "to", {})}});
  }
  if (kind == "select_output") return actions::select_output(state, port_field(action, "output"));
  if (kind == "set_output") return actions::set_graph_output(state, port_field(action, "output"));
  if (kind == "delete") return actions::delete_nodes(state, nodes_field(action));
  if (kind == "duplicate") {
    actions::select(state, nodes_field(action));
    return actions::duplicate_selection(state);
  }
  if (kind == "select") {
    actions::select(state, nodes_field(action));
    return Ok{};
  }
  if (kind == "undo") return status_of(actions::undo(state), "nothing to undo");
  if (kind == "redo") return status_of(actions::redo(state), "nothing to redo");
  if (kind == "save") {
    return action.contains("path")
               ? actions::save_as(state, text_field(action, "path"), action.value("replace", false))
               : actions::save(state);
  }
  if (kind == "frame") {
    if (!action.contains("frame") || !action["frame"].is_number_integer()) {
      throw std::invalid_argument("needs an integer \"frame\"");
    }
    actions::set_frame(state, action["frame"].get<int>());
    return Ok{};
  }
  return std::nullopt;
}

// Menus, keys, clipboard, groups and views: the actions that need more than the document.
Status run_other_action(EditorState& state, const std::string& kind, const nlohmann::json& action,
                        const ScriptHooks& hooks) {
  if (kind == "open") return actions::open(state, text_field(action, "path"));
  if (kind == "expect_status") {  // the status line as the user sees it now
    const std::string wanted = text_field(action, "contains");
    if (state.status.find(wanted) != std::string::npos) return Ok{};
    return make_error("the status line says '" + state.status + "', not '" + wanted + "'");
  }
  if (kind == "recover") {  // what the recovery prompt's "recover" does
    Status recovered = state.doc.recover();
    actions::report(state, recovered, "recovered the autosave");
    return recovered;
  }
  if (kind == "add_menu") {
    if (hooks.add_menu) hooks.add_menu(action.value("filter", std::string()));
    return Ok{};
  }
  if (kind == "key") {
    if (!hooks.key) throw std::invalid_argument("key presses need the editor window");
    return hooks.key(text_field(action, "chord"));
  }
  if (kind == "copy") {
    std::string copied = actions::copy_selection(state);
    if (copied.empty()) return make_error(state.status);
    clipboard() = copied;
    if (hooks.set_clipboard) hooks.set_clipboard(copied);
    return Ok{};
  }
  if (kind == "paste") {
    std::string text = hooks.get_clipboard ? hooks.get_clipboard() : clipboard();
    std::optional<Position> at;
    if (action.contains("at")) at = position_field(action, "at", {});
    return actions::paste(state, text, at);
  }
  if (kind == "rename") {
    return actions::rename(state, text_field(action, "node"), text_field(action, "to"));
  }
  if (kind == "bypass") {
    actions::select(state, nodes_field(action));
    return actions::toggle_bypass(state);
  }
  if (kind == "auto_layout") return actions::auto_layout(state);
  if (kind == "dot") {
    PortRef to = port_field(action, "to");
    Status added = state.doc.add_reroute(to.node, to.port, position_field(action, "at", {0, 0}));
    actions::report(state, added, "added a dot to the link into " + to.str());
    return added;
  }
  if (kind == "view") {
    if (!hooks.view) throw std::invalid_argument("view options need the editor window");
    return hooks.view(action);
  }
  if (kind == "backdrop") {
    actions::select(state, nodes_field(action));
    return actions::backdrop_around_selection(state,
                                              action.value("label", std::string("Backdrop")));
  }
  if (kind == "insert") {
    Position at = position_field(action, "at", {0, 0});
    std::string type = text_field(action, "type");
    if (action.contains("on")) {
      PortRef on = port_field(action, "on");
      auto inserted = actions::insert_on_link(state, type, at, on.node, on.port);
      return inserted ? Status(Ok{}) : Status(inserted.error());
    }
    PortRef after = port_field(action, "after");
    actions::select(state, {after.node});
    auto inserted = actions::add_node_at_cursor(state, type, at);
    return inserted ? Status(Ok{}) : Status(inserted.error());
  }
  if (kind == "compare") {
    if (!action.contains("output") || action["output"].is_null()) {
      return actions::compare_with(state, std::nullopt);
    }
    return actions::compare_with(state, port_field(action, "output"));
  }
  if (kind == "group") {
    if (action.contains("nodes")) actions::select(state, nodes_field(action));
    return actions::group_selection(state);
  }
  if (kind == "ungroup") {
    if (action.contains("nodes")) actions::select(state, nodes_field(action));
    return actions::ungroup_selection(state);
  }
  if (kind == "collapse" || kind == "expand") {
    return actions::set_group_collapsed(state, text_field(action, "group"), kind == "collapse");
  }
  if (kind == "drop") {
    if (!hooks.drop) throw std::invalid_argument("dropping files needs the editor window");
    std::vector<std::string> paths;
    for (const auto& path : action.value("paths", nlohmann::json::array())) {
      if (!path.is_string()) throw std::invalid_argument("\"paths\" must hold file paths");
      paths.push_back(path.get<std::string>());
    }
    if (paths.empty()) throw std::invalid_argument("needs \"paths\": [files]");
    return hooks.drop(paths);
  }
  if (kind == "expect_view") {
    if (!hooks.expect_view) throw std::invalid_argument("expect_view needs the editor window");
    return hooks.expect_view(action);
  }
  if (kind == "fit") {
    if (hooks.fit) hooks.fit(action.value("whole", false));
    return Ok{};
  }
  throw std::invalid_argument(
      "unknown action '" + kind +
      "' (add_node, link, unlink, set_param, move, select_output, "
      "set_output, delete, duplicate, select, undo, redo, save, frame, fit, add_menu, play, key, "
      "copy, paste, rename, bypass, auto_layout, insert, backdrop, wait, view, dot, group, "
      "ungroup, collapse, expand, compare, open, recover, expect_status, drop, expect_view, click, "
      "hover, drag)");
}

Status run_action(EditorState& state, const nlohmann::json& action, const ScriptHooks& hooks) {
  const std::string kind = text_field(action, "do");
  if (std::optional<Status> edited = run_edit_action(state, kind, action)) return *edited;
  return run_other_action(state, kind, action, hooks);
}

}  // namespace

Result<nlohmann::json> read_script(const std::string& path) {
  std::string text, why;
  if (!files::read_regular_file(path, kMaxEditorFileBytes, &text, &why)) {
    return make_error("cannot open the script " + quote_for_message(path) + ": " + why);
  }
  nlohmann::json script = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (script.is_discarded()) return make_error("the script '" + path + "' is not valid JSON");
  if (script.is_object() && script.contains("actions")) script = script["actions"];
  if (!script.is_array()) {
    return make_error("the script '" + path +
                      "' must be a list of actions or {\"actions\": [...]}");
  }
  return script;
}

namespace {

bool is_mouse_action(const nlohmann::json& action) {
  std::string kind = action.value("do", std::string());
  return kind == "drag_link" || kind == "drag_node" || kind == "click_output" || kind == "wheel" ||
         kind == "double_click_link" || kind == "click" || kind == "hover" || kind == "drag";
}

std::string describe(size_t index, const nlohmann::json& action) {
  std::string where = "script action " + std::to_string(index + 1);
  if (action.is_object()) where += " (" + action.value("do", std::string("?")) + ")";
  return where;
}

}  // namespace

Status ScriptRunner::judge(EditorState& state, const Status& outcome) {
  const nlohmann::json& action = actions_[next_ - 1];
  std::string where = describe(next_ - 1, action);
  std::string expect = action.value("expect", std::string("ok"));
  if (expect == "ok" && !outcome) return make_error(where + " was refused: " + outcome.message());
  if (expect == "refused" && outcome) return make_error(where + " was expected to be refused");
  std::fprintf(stderr, "%s: %s\n", where.c_str(),
               outcome ? (state.status.empty() ? "done" : state.status.c_str())
                       : ("refused as expected: " + outcome.message()).c_str());
  return Ok{};
}

Status ScriptRunner::step(EditorState& state, const ScriptHooks& hooks,
                          std::vector<MouseFrame>* gesture_frames) {
  if (wait_frames_ > 0) {
    --wait_frames_;
    return Ok{};
  }
  if (play_until_ >= 0) {
    // Playback runs at the editor's own pace; the action ends once that frame is on screen.
    const int shown = hooks.shown_frame ? hooks.shown_frame() : play_until_;
    if (shown < play_until_ && state.playing) return Ok{};
    state.playing = false;
    play_until_ = -1;
    state.status = "played to frame " + std::to_string(state.frame);
    if (hooks.playback_fps) {
      char reached[96];
      std::snprintf(reached, sizeof reached, " (reached %.2f fps of the graph's %g)",
                    hooks.playback_fps(), state.doc.graph().settings.fps);
      state.status += reached;
    }
    if (Status judged = judge(state, Ok{}); !judged) return judged;
  }
  if (waiting_) {
    if (!gesture_frames->empty()) return Ok{};  // still playing
    waiting_ = false;
    // The canvas reports a refused drop on the status line and counts it.
    Status outcome =
        state.refused_count > refused_before_ ? Status(make_error(state.status)) : Status(Ok{});
    if (Status judged = judge(state, outcome); !judged) return judged;
  }
  while (next_ < actions_.size()) {
    const nlohmann::json& action = actions_[next_];
    std::string where = describe(next_, action);
    if (!action.is_object()) return make_error(where + ": must be an object {\"do\": ...}");
    std::string expect = action.value("expect", std::string("ok"));
    if (expect != "ok" && expect != "refused") {
      return make_error(where + ": \"expect\" must be \"ok\" or \"refused\"");
    }
    if (is_mouse_action(action)) {
      // The canvas must have drawn the graph as it is now before its layout can be aimed at.
      if (!laid_out_) {
        laid_out_ = true;
        return Ok{};
      }
      if (!hooks.gesture) return make_error(where + ": mouse actions need the editor window");
      auto frames = hooks.gesture(action);
      if (!frames) return make_error(where + ": " + frames.message());
      *gesture_frames = std::move(*frames);
      refused_before_ = state.refused_count;
      state.status.clear();
      waiting_ = true;
      laid_out_ = false;
      ++next_;
      return Ok{};
    }
    if (action.value("do", std::string()) == "wait") {
      wait_frames_ = std::max(action.value("frames", 1), 0);
      ++next_;
      state.status = "waited " + std::to_string(wait_frames_) + " frames";
      if (Status judged = judge(state, Ok{}); !judged) return judged;
      return Ok{};
    }
    if (action.value("do", std::string()) == "play") {
      const int frames = action.value("frames", 1);
      const Settings& settings = state.doc.graph().settings;
      play_until_ = std::min(state.frame + std::max(frames, 1), settings.last_frame);
      ++next_;
      if (!hooks.shown_frame) {  // no window: the frame is simply set
        state.frame = play_until_;
        play_until_ = -1;
        if (Status judged = judge(state, Ok{}); !judged) return judged;
        continue;
      }
      state.playing = true;
      return Ok{};
    }
    Status outcome = Ok{};
    if (action.value("do", std::string()) != "expect_status") state.status.clear();
    try {
      outcome = run_action(state, action, hooks);
    } catch (const std::exception& bad) {  // malformed action, not a refused edit
      return make_error(where + ": " + bad.what());
    }
    ++next_;
    laid_out_ = false;
    if (Status judged = judge(state, outcome); !judged) return judged;
    // A key press or a drop is handled by the next frame: the following actions wait for it.
    const std::string done = action.value("do", std::string());
    if (done == "key" || done == "drop") return Ok{};
  }
  return Ok{};
}

Status run_script(EditorState& state, const nlohmann::json& script, const ScriptHooks& hooks) {
  ScriptRunner runner(script);
  std::vector<MouseFrame> frames;
  while (!runner.finished()) {
    Status stepped = runner.step(state, hooks, &frames);
    if (!stepped) return stepped;
    if (!frames.empty()) return make_error("mouse actions need the editor window");
  }
  return Ok{};
}

}  // namespace aq::editor
