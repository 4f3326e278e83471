#include "scene_watcher.h"

namespace tl::editor {

void SceneWatcher::watch(std::vector<std::filesystem::path> files, double now) {
  files_ = std::move(files);
  loaded_ = stamp();
  pending_.reset();
  lastPoll_ = now;
}

std::vector<SceneWatcher::Stamp> SceneWatcher::stamp() const {
  std::vector<Stamp> stamps;
  for (const auto& file : files_) {
    Stamp s;
    std::error_code ec;
    s.modified = std::filesystem::last_write_time(file, ec);
    if (!ec) s.size = std::filesystem::file_size(file, ec);
    s.exists = !ec;
    stamps.push_back(s);
  }
  return stamps;
}

bool SceneWatcher::changed(double now) {
  if (files_.empty() || now - lastPoll_ < kPollSeconds) return false;
  lastPoll_ = now;
  std::vector<Stamp> current = stamp();
  if (current == loaded_) {
    pending_.reset();  // written back as it was
    return false;
  }
  // The scene file missing is an export in progress (removed, then written): wait for it.
  if (!current.front().exists) return false;
  if (!pending_ || *pending_ != current) {
    pending_ = current;
    pendingSince_ = now;
    return false;
  }
  if (now - pendingSince_ < kSettleSeconds) return false;
  loaded_ = current;
  pending_.reset();
  return true;
}

}  // namespace tl::editor
