// A small file chooser in ImGui (the Debian ImGui has none): a path field and the entries of
// its folder. Used by File > Open / Save As and by path parameters.
#pragma once

#include <string>

namespace aq::editor {

class FileDialog {
 public:
  // Opens the modal popup `title` next frame, starting at `path` (a file or a folder).
  void open(const std::string& title, const std::string& path);
  // Draws the popup if open; returns true once, when the user accepted a path.
  bool draw(std::string* chosen);
  const std::string& title() const { return title_; }

 private:
  std::string title_;
  std::string path_;
  bool pending_open_ = false;
};

}  // namespace aq::editor
