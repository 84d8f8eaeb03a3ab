// The ImGui file chooser. See file_dialog.h.
#include "file_dialog.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <filesystem>
#include <system_error>
#include <vector>

namespace aq::editor {

namespace fs = std::filesystem;

void FileDialog::open(const std::string& title, const std::string& path) {
  title_ = title;
  std::error_code error;
  path_ = path.empty() ? fs::current_path(error).string() + "/" : path;
  pending_open_ = true;
}

bool FileDialog::draw(std::string* chosen) {
  if (title_.empty()) return false;
  if (pending_open_) {
    ImGui::OpenPopup(title_.c_str());
    pending_open_ = false;
  }
  ImGui::SetNextWindowSize(ImVec2(560, 420), ImGuiCond_Appearing);
  if (!ImGui::BeginPopupModal(title_.c_str())) return false;
  bool accepted = false;
  ImGui::SetNextItemWidth(-1);
  if (ImGui::InputText("##path", &path_, ImGuiInputTextFlags_EnterReturnsTrue)) accepted = true;

  std::error_code error;
  fs::path folder =
      fs::is_directory(path_, error) ? fs::path(path_) : fs::path(path_).parent_path();
  if (folder.empty()) folder = ".";
  std::vector<fs::directory_entry> entries;
  for (const auto& entry : fs::directory_iterator(folder, error)) entries.push_back(entry);
  std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) {
    if (a.is_directory() != b.is_directory()) return a.is_directory();
    return a.path().filename() < b.path().filename();
  });
  ImGui::BeginChild("##entries", ImVec2(0, -ImGui::GetFrameHeightWithSpacing()), true);
  if (ImGui::Selectable("../")) path_ = fs::absolute(folder, error).parent_path().string() + "/";
  for (const auto& entry : entries) {
    std::string name = entry.path().filename().string();
    if (name.empty() || name[0] == '.') continue;
    bool is_folder = entry.is_directory(error);
    if (ImGui::Selectable((name + (is_folder ? "/" : "")).c_str(), false,
                          ImGuiSelectableFlags_AllowDoubleClick)) {
      path_ = entry.path().string() + (is_folder ? "/" : "");
      if (!is_folder && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) accepted = true;
    }
  }
  ImGui::EndChild();
  if (ImGui::Button("OK")) accepted = true;
  ImGui::SameLine();
  bool cancelled =
      ImGui::Button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape));
  if (accepted && !fs::is_directory(path_, error)) {
    *chosen = path_;
    ImGui::CloseCurrentPopup();
    title_.clear();
  } else if (accepted) {
    accepted = false;  // a folder: keep browsing
  }
  if (cancelled) {
    ImGui::CloseCurrentPopup();
    title_.clear();
  }
  ImGui::EndPopup();
  return accepted;
}

}  // namespace aq::editor
