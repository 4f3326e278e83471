// Notices when the scene's file changes on disk (an artist re-exported it), so the editor can
// reload it. Polled from the UI loop: a stat of a few files a quarter second, no thread.
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

namespace tl::editor {

class SceneWatcher {
 public:
  // Watches `files` (the scene file first; its buffers and textures may follow); none stops.
  void watch(std::vector<std::filesystem::path> files, double now);
  // True once when the watched files changed and then stayed unchanged for `settle` seconds:
  // an exporter that writes the .gltf, then the .bin, is not reloaded half way.
  bool changed(double now);

  static constexpr double kPollSeconds = 0.25;
  static constexpr double kSettleSeconds = 0.5;

 private:
  struct Stamp {
    std::filesystem::file_time_type modified{};
    uintmax_t size = 0;
    bool exists = false;
    bool operator==(const Stamp&) const = default;
  };
  std::vector<Stamp> stamp() const;

  std::vector<std::filesystem::path> files_;
  std::vector<Stamp> loaded_;                  // as the editor last loaded them
  std::optional<std::vector<Stamp>> pending_;  // a change seen, waiting to settle
  double pendingSince_ = 0.0, lastPoll_ = 0.0;
};

}  // namespace tl::editor
