// The ImGui file chooser. See file_dialog.h.
#include "file_dialog.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <filesystem>
#include <system_error>

namespace aq::editor {

namespace fs = std::filesystem;

std::vector<FolderEntry> list_folder(const std::string& folder,
                                     const std::vector<std::string>& extensions) {
  std::vector<FolderEntry> entries;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(folder.empty() ? "." : folder, error)) {
    std::string name = entry.path().filename().string();
    if (name.empty() || name[0] == '.') continue;
    const bool is_folder = entry.is_directory(error);
    if (!is_folder) {
      if (name.ends_with(".autosave.json")) continue;  // side files, offered at open
      const bool wanted =
          extensions.empty() || std::any_of(extensions.begin(), extensions.end(),
                                            [&](const auto& ext) { return name.ends_with(ext); });
      if (!wanted) continue;
    }
    entries.push_back({name, is_folder});
  }
  std::sort(entries.begin(), entries.end(), [](const FolderEntry& a, const FolderEntry& b) {
    if (a.is_folder != b.is_folder) return a.is_folder;
    return a.name < b.name;
  });
  return entries;
}

void FileDialog::open(const std::string& title, const std::string& path,
                      std::vector<std::string> extensions) {
  title_ = title;
  extensions_ = std::move(extensions);
  all_files_ = false;
  std::error_code error;
  fs::path start = path.empty() ? fs::current_path(error) : fs::absolute(path, error);
  if (fs::is_directory(start, error)) {
    folder_ = start.string();
    path_ = "";
  } else {
    folder_ = start.parent_path().string();
    path_ = start.filename().string();
  }
  pending_open_ = true;
}

bool FileDialog::draw(std::string* chosen) {
  if (title_.empty()) return false;
  if (pending_open_) {
    ImGui::OpenPopup(title_.c_str());
    pending_open_ = false;
  }
  ImGui::SetNextWindowSize(ImVec2(600, 440), ImGuiCond_Appearing);
  if (!ImGui::BeginPopupModal(title_.c_str())) return false;
  bool accepted = false;
  std::error_code error;
  ImGui::TextDisabled("folder");
  ImGui::SameLine();
  ImGui::TextUnformatted(folder_.c_str());
  ImGui::SetNextItemWidth(-1);
  if (ImGui::InputTextWithHint("##name", "file name", &path_,
                               ImGuiInputTextFlags_EnterReturnsTrue)) {
    accepted = true;
  }

  const auto entries = list_folder(folder_, all_files_ ? std::vector<std::string>{} : extensions_);
  std::string enter;  // a folder to go into after the list is drawn
  ImGui::BeginChild("##entries", ImVec2(0, -ImGui::GetFrameHeightWithSpacing()), true);
  if (ImGui::Selectable("../", false, ImGuiSelectableFlags_AllowDoubleClick) &&
      ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) {
    enter = fs::path(folder_).parent_path().string();
  }
  for (const auto& entry : entries) {
    const std::string label = entry.name + (entry.is_folder ? "/" : "");
    const bool selected = !entry.is_folder && entry.name == path_;
    if (ImGui::Selectable(label.c_str(), selected, ImGuiSelectableFlags_AllowDoubleClick)) {
      const bool twice = ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left);
      if (entry.is_folder) {
        // One click only selects, so the list does not change under a double-click's second click.
        if (twice) enter = (fs::path(folder_) / entry.name).string();
      } else {
        path_ = entry.name;
        if (twice) accepted = true;
      }
    }
  }
  if (entries.empty()) ImGui::TextDisabled("no graph files here");
  ImGui::EndChild();
  if (!enter.empty()) {
    folder_ = fs::weakly_canonical(enter, error).string();
  }
  if (ImGui::Button("OK")) accepted = true;
  ImGui::SameLine();
  bool cancelled =
      ImGui::Button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape));
  if (!extensions_.empty()) {
    ImGui::SameLine();
    ImGui::Checkbox("all files", &all_files_);
  }
  std::string full = fs::path(path_).is_absolute() ? path_ : (fs::path(folder_) / path_).string();
  if (accepted && fs::is_directory(full, error)) {
    folder_ = fs::weakly_canonical(full, error).string();  // a folder typed: go there
    path_.clear();
    accepted = false;
  } else if (accepted && path_.empty()) {
    accepted = false;
  }
  if (accepted) {
    *chosen = full;
    ImGui::CloseCurrentPopup();
    title_.clear();
  }
  if (cancelled) {
    ImGui::CloseCurrentPopup();
    title_.clear();
  }
  ImGui::EndPopup();
  return accepted;
}

}  // namespace aq::editor
