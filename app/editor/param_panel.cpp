// The parameter panel. See param_panel.h.
#include "param_panel.h"

#include "editor_actions.h"
#include "item_rects.h"
#include "node_advice.h"
#include "param_widgets.h"

#include <aquarelle/core/graph_io.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <filesystem>

namespace aq::editor {

namespace {

namespace fs = std::filesystem;

// A path parameter is stored relative to the graph's folder when it lies under it, so a graph
// and its textures move together.
std::string relative_to_graph(const std::string& graph_path, const std::string& chosen) {
  if (graph_path.empty()) return chosen;
  std::error_code error;
  fs::path base = fs::absolute(graph_path, error).parent_path();
  fs::path relative = fs::relative(fs::absolute(chosen, error), base, error);
  if (error || relative.empty() || relative.string().rfind("..", 0) == 0) return chosen;
  return relative.string();
}

// After a continuous widget: ends the undo step when the user lets go.
void end_gesture_after_edit(EditorState& state) {
  if (ImGui::IsItemDeactivatedAfterEdit()) actions::end_gesture(state);
}

}  // namespace

void ParamPanel::draw(EditorState& state, const NodeFeedback& feedback) {
  const auto group =
      state.selection.size() == 1 ? group_name_of_item(*state.selection.begin()) : std::nullopt;
  if (group) {
    draw_group(state, *group, feedback);
  } else if (state.selection.size() == 1 &&
             state.doc.graph().nodes.count(*state.selection.begin())) {
    draw_node(state, *state.selection.begin(), feedback);
  } else {
    if (state.selection.size() > 1) {
      ImGui::TextDisabled("%zu nodes selected", state.selection.size());
      ImGui::Separator();
    }
    draw_settings(state);
  }
  std::string chosen;
  if (file_dialog_.draw(&chosen)) {
    auto split = file_target_.find('\n');
    std::string node = file_target_.substr(0, split);
    std::string param = file_target_.substr(split + 1);
    (void)actions::set_param(state, node, param, relative_to_graph(state.doc.path(), chosen));
  }
}

void ParamPanel::draw_group(EditorState& state, const std::string& name,
                            const NodeFeedback& feedback) {
  std::vector<std::string> members;
  for (const auto& group : read_groups(state.doc.graph())) {
    if (group.name == name) members = group.nodes;
  }
  if (members.empty()) return;
  // The group's nodes to pick from; the picked one's parameters below.
  if (std::find(members.begin(), members.end(), group_member_) == members.end()) {
    group_member_ = members.front();
  }
  ImGui::Text("group %s: %zu nodes", name.c_str(), members.size());
  if (ImGui::BeginListBox("##members",
                          ImVec2(-1, ImGui::GetTextLineHeightWithSpacing() *
                                         std::min<float>(members.size() + 0.5f, 6.5f)))) {
    for (const auto& id : members) {
      const std::string label = id + "  (" + state.doc.graph().nodes.at(id).type + ")";
      if (ImGui::Selectable(label.c_str(), id == group_member_)) group_member_ = id;
    }
    ImGui::EndListBox();
  }
  ImGui::Separator();
  draw_node(state, group_member_, feedback);
}

void ParamPanel::draw_node(EditorState& state, const std::string& id,
                           const NodeFeedback& feedback) {
  const Node& node = state.doc.graph().nodes.at(id);
  const NodeType* type = state.doc.registry().find(node.type);
  ImGui::Text("%s", id.c_str());
  ImGui::SameLine();
  ImGui::TextDisabled("(%s)", node.type.c_str());
  if (type == nullptr) {
    ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "type '%s' is not installed", node.type.c_str());
    return;
  }
  if (!type->description.empty()) ImGui::TextWrapped("%s", type->description.c_str());
  auto timing = feedback.timings.find(id);
  if (timing != feedback.timings.end()) {
    ImGui::TextDisabled("%s: gpu %.3f ms, cpu %.3f ms", timing->second.cached ? "cached" : "ran",
                        timing->second.gpu_ms, timing->second.cpu_ms);
  }
  ImGui::PushTextWrapPos(0);
  // The same advice as the node's tooltip on the canvas.
  for (const auto& reason :
       node_advice(state.doc, id, feedback.error_node == id ? feedback.error : "")) {
    ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "%s", reason.c_str());
  }
  ImGui::PopTextWrapPos();

  if (!type->inputs.empty() && ImGui::CollapsingHeader("Inputs", ImGuiTreeNodeFlags_DefaultOpen)) {
    for (const auto& port : type->inputs) {
      ImGui::PushID(port.name.c_str());
      auto link = node.inputs.find(port.name);
      if (link != node.inputs.end()) {
        ImGui::Text("%s <- %s", port.name.c_str(), link->second.str().c_str());
        ImGui::SameLine();
        if (ImGui::SmallButton("unlink")) (void)actions::unlink(state, id, port.name);
      } else {
        ImGui::TextDisabled("%s: %s", port.name.c_str(),
                            port.optional ? "(optional)" : "not linked");
      }
      ImGui::PopID();
    }
  }

  draw_params(state, id, *type);
}

void ParamPanel::draw_params(EditorState& state, const std::string& id, const NodeType& type) {
  if (type.params.empty()) return;
  if (!ImGui::CollapsingHeader("Parameters", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const Node& node = state.doc.graph().nodes.at(id);
  for (const ParamInfo& param : type.params) {
    ImGui::PushID(param.name.c_str());
    const nlohmann::json value = param_value_or_default(node, param);
    if (param.type == AQ_PARAM_PATH) {
      if (ImGui::Button("...")) {
        file_target_ = id + "\n" + param.name;
        const std::string text = value.is_string() ? value.get<std::string>() : "";
        fs::path start = fs::path(state.doc.path()).parent_path() / text;
        file_dialog_.open("Choose a file for " + id + "." + param.name, start.string(), {});
      }
      ImGui::SameLine();
    }
    auto edit = draw_param_widget(param, value);
    note_item("param:" + param.name);  // scripted gestures aim at it by this name
    if (edit) {
      (void)actions::set_param(state, id, param.name, edit->value, edit->continuous);
    }
    end_gesture_after_edit(state);
    if (ImGui::BeginPopupContextItem("##reset")) {
      if (ImGui::MenuItem("reset to default")) {
        (void)actions::set_param(state, id, param.name, nullptr);
      }
      ImGui::EndPopup();
    }
    // The description while hovering, never while dragging: it would hide the value.
    if (ImGui::IsItemHovered() && !ImGui::IsItemActive() && !param.description.empty()) {
      ImGui::SetTooltip("%s", param.description.c_str());
    }
    ImGui::PopID();
  }
}

void ParamPanel::draw_settings(EditorState& state) {
  const Graph& graph = state.doc.graph();
  // A drag edits a pending copy; the document changes once, when the drag ends.
  Settings settings = pending_settings_.value_or(graph.settings);
  ImGui::TextUnformatted("Graph settings");
  bool commit = false;
  int size[2] = {settings.width, settings.height};
  if (ImGui::DragInt2("resolution", size, 1.0f, 1, 16384)) {
    settings.width = std::max(size[0], 1);
    settings.height = std::max(size[1], 1);
  }
  commit |= ImGui::IsItemDeactivatedAfterEdit();
  float fps = static_cast<float>(settings.fps);
  if (ImGui::DragFloat("fps", &fps, 0.1f, 1.0f, 240.0f)) settings.fps = fps;
  commit |= ImGui::IsItemDeactivatedAfterEdit();
  int frames[2] = {settings.first_frame, settings.last_frame};
  if (ImGui::DragInt2("frames", frames, 1.0f)) {
    settings.first_frame = frames[0];
    settings.last_frame = std::max(frames[0], frames[1]);
  }
  commit |= ImGui::IsItemDeactivatedAfterEdit();
  const char* precisions[] = {"half", "float"};
  int precision = settings.precision == "float" ? 1 : 0;
  if (ImGui::Combo("precision", &precision, precisions, 2)) {
    settings.precision = precisions[precision];
    commit = true;
  }
  const char* qualities[] = {"draft", "preview", "final"};
  int quality = settings.quality == "draft" ? 0 : settings.quality == "preview" ? 1 : 2;
  if (ImGui::Combo("quality", &quality, qualities, 3)) {
    settings.quality = qualities[quality];
    commit = true;
  }
  if (commit) {
    actions::report(state, state.doc.set_settings(settings), "settings changed");
    pending_settings_.reset();
  } else if (ImGui::IsAnyItemActive()) {
    pending_settings_ = settings;
  } else {
    pending_settings_.reset();
  }
  ImGui::Text("output: %s", graph.output ? graph.output->str().c_str() : "(none)");
  ImGui::TextDisabled("select a node to edit its parameters");
}

}  // namespace aq::editor
