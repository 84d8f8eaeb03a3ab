// File > Open Recent: the graphs last opened or saved, newest first, kept across sessions in
// $XDG_CONFIG_HOME/aquarelle/recent.json (~/.config/... without it). No GL.
#pragma once

#include <string>
#include <vector>

namespace aq::editor {

class RecentFiles {
 public:
  static constexpr size_t kKept = 10;
  // `store`: the JSON file the list lives in; "" keeps it in memory only (the scripted mode, so
  // tests never touch the user's list).
  explicit RecentFiles(std::string store);
  // `path` (made absolute) moves to the front; the list is written back.
  void add(const std::string& path);
  const std::vector<std::string>& paths() const { return paths_; }

 private:
  std::string store_;
  std::vector<std::string> paths_;
};

// Where the list is kept for this user; "" when there is no home folder.
std::string default_recent_store();

}  // namespace aq::editor
