// A small file chooser in ImGui (the Debian ImGui has none): the folder shown on top, a path
// field and the folder's entries, graph files (*.json) only unless "all files" is ticked. A
// click selects, a double-click opens a folder or accepts a file. Used by File > Open / Save As
// (graph files) and by path parameters (all files).
#pragma once

#include <string>
#include <vector>

namespace aq::editor {

struct FolderEntry {
  std::string name;  // file name, no folder
  bool is_folder = false;
};

// The entries of `folder` a chooser lists: folders first, then files, each sorted by name;
// hidden entries and autosave side files left out; files only when they end with one of
// `extensions` (empty: every file).
std::vector<FolderEntry> list_folder(const std::string& folder,
                                     const std::vector<std::string>& extensions);

class FileDialog {
 public:
  // Opens the modal popup `title` next frame, starting at `path` (a file or a folder), listing
  // files with those extensions (empty: all files).
  void open(const std::string& title, const std::string& path,
            std::vector<std::string> extensions = {".json"});
  // Draws the popup if open; returns true once, when the user accepted a path.
  bool draw(std::string* chosen);
  const std::string& title() const { return title_; }

 private:
  std::string title_;
  std::string folder_;
  std::string path_;
  std::vector<std::string> extensions_;
  bool all_files_ = false;
  bool pending_open_ = false;
};

}  // namespace aq::editor
