// Recently opened graphs. See recent_files.h.
#include "recent_files.h"

#include <aquarelle/sdk/regular_file.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace aq::editor {

namespace fs = std::filesystem;

namespace {
constexpr uint64_t kMaxStoreBytes = 1 << 20;  // ten paths need far less
}  // namespace

RecentFiles::RecentFiles(std::string store) : store_(std::move(store)) {
  if (store_.empty()) return;
  std::string text, why;  // a FIFO or device in its place is ignored, never waited on
  if (!files::read_regular_file(store_, kMaxStoreBytes, &text, &why)) return;
  const nlohmann::json list = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!list.is_array()) return;  // unreadable: start a new list rather than fail
  for (const auto& item : list) {
    if (item.is_string() && paths_.size() < kKept) paths_.push_back(item.get<std::string>());
  }
}

void RecentFiles::add(const std::string& path) {
  std::error_code error;
  fs::path absolute = fs::absolute(path, error);
  const std::string entry = error ? path : absolute.lexically_normal().string();
  std::erase(paths_, entry);
  paths_.insert(paths_.begin(), entry);
  if (paths_.size() > kKept) paths_.resize(kKept);
  if (store_.empty()) return;
  fs::create_directories(fs::path(store_).parent_path(), error);
  std::ofstream out(store_ + ".tmp");
  out << nlohmann::json(paths_).dump(2) << "\n";
  out.close();
  if (out) fs::rename(store_ + ".tmp", store_, error);
}

std::string default_recent_store() {
  if (const char* config = std::getenv("XDG_CONFIG_HOME"); config != nullptr && *config) {
    return (fs::path(config) / "aquarelle" / "recent.json").string();
  }
  if (const char* home = std::getenv("HOME"); home != nullptr && *home) {
    return (fs::path(home) / ".config" / "aquarelle" / "recent.json").string();
  }
  return "";
}

}  // namespace aq::editor
