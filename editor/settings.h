// What the editor remembers between runs, in $XDG_CONFIG_HOME/twinlight (or
// ~/.config/twinlight): recent scenes, render scale, vsync, lighting path, camera bookmarks,
// the albedo database and the saved render settings per scene, how often unsaved work is
// written to the recovery folder beside it, and Dear ImGui's window layout (imgui.ini beside
// settings.json).
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace tl::editor {

struct Settings {
  std::vector<std::string> recentScenes;  // most recent first, at most 10
  float renderScale = 0.5f;               // engine resolution / viewport resolution
  bool vsync = true;
  std::string lightingPath = "direct";
  int windowWidth = 1600, windowHeight = 900;
  nlohmann::json bookmarks = nlohmann::json::object();  // scene path -> {"1": camera, ...}
  nlohmann::json albedoDatabases = nlohmann::json::object();  // scene path -> its albedo database
  nlohmann::json sceneSettings = nlohmann::json::object();    // scene path -> its saved render settings (File > Save)
  // Seconds between writes of unsaved work to the recovery file (1 to 60: a crash loses at most
  // that much work).
  int autosaveSeconds = 30;

  void addRecent(const std::string& scene);
};

std::filesystem::path configDirectory();
// A missing or unreadable file gives the defaults (and a warning), never an error.
Settings loadSettings();
nlohmann::json toJson(const Settings& settings);
// Written atomically; throws SessionError naming the file when it cannot be written.
void saveSettings(const Settings& settings);

}  // namespace tl::editor
