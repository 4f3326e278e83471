#include "settings.h"

#include "session/image_io.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>

namespace tl::editor {

void Settings::addRecent(const std::string& scene) {
  recentScenes.erase(std::remove(recentScenes.begin(), recentScenes.end(), scene), recentScenes.end());
  recentScenes.insert(recentScenes.begin(), scene);
  if (recentScenes.size() > 10) recentScenes.resize(10);
}

std::filesystem::path configDirectory() {
  if (const char* x = std::getenv("XDG_CONFIG_HOME"); x && *x) return std::filesystem::path(x) / "twinlight";
  if (const char* h = std::getenv("HOME"); h && *h) return std::filesystem::path(h) / ".config" / "twinlight";
  return std::filesystem::temp_directory_path() / "twinlight-config";
}

Settings loadSettings() {
  Settings s;
  auto file = configDirectory() / "settings.json";
  std::ifstream in(file);
  if (!in) return s;
  try {
    auto j = nlohmann::json::parse(in);
    s.recentScenes = j.value("recentScenes", s.recentScenes);
    s.renderScale = std::clamp(j.value("renderScale", s.renderScale), 0.1f, 2.0f);
    s.vsync = j.value("vsync", s.vsync);
    s.lightingPath = j.value("lightingPath", s.lightingPath);
    s.windowWidth = std::clamp(j.value("windowWidth", s.windowWidth), 320, 16384);
    s.windowHeight = std::clamp(j.value("windowHeight", s.windowHeight), 240, 16384);
    if (j.contains("bookmarks") && j["bookmarks"].is_object()) s.bookmarks = j["bookmarks"];
    if (j.contains("albedoDatabases") && j["albedoDatabases"].is_object()) s.albedoDatabases = j["albedoDatabases"];
    if (j.contains("sceneSettings") && j["sceneSettings"].is_object()) s.sceneSettings = j["sceneSettings"];
    s.autosaveSeconds = std::clamp(j.value("autosaveSeconds", s.autosaveSeconds), 1, 60);
  } catch (const std::exception& e) {
    spdlog::warn("{}: ignored ({}); using defaults", file.string(), e.what());
  }
  return s;
}

nlohmann::json toJson(const Settings& s) {
  return {{"recentScenes", s.recentScenes}, {"renderScale", s.renderScale}, {"vsync", s.vsync},
          {"lightingPath", s.lightingPath}, {"windowWidth", s.windowWidth}, {"windowHeight", s.windowHeight},
          {"bookmarks", s.bookmarks}, {"albedoDatabases", s.albedoDatabases}, {"sceneSettings", s.sceneSettings},
          {"autosaveSeconds", s.autosaveSeconds}};
}

void saveSettings(const Settings& s) {
  session::writeTextFile(configDirectory() / "settings.json", toJson(s).dump(2) + "\n");
}

}  // namespace tl::editor
