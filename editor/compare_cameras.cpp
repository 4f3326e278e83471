#include "compare_cameras.h"

#include "camera_controller.h"
#include "settings.h"

#include <fmt/format.h>

#include <sstream>

namespace tl::editor {
namespace {

// The bookmarks saved for a scene, keyed by slot ("1".."9").
nlohmann::json bookmarksOf(const std::filesystem::path& sceneFile) {
  const std::string key = std::filesystem::absolute(sceneFile).string();
  const Settings settings = loadSettings();
  return settings.bookmarks.contains(key) ? settings.bookmarks[key] : nlohmann::json::object();
}

std::string sceneName(const std::filesystem::path& sceneFile) { return sceneFile.stem().string(); }

size_t sceneCameraCount(const std::filesystem::path& sceneFile) {
  return session::Session::parseScene(sceneFile)->cameras.size();
}

}  // namespace

std::vector<std::string> compareCameraNames(const std::filesystem::path& sceneFile, const std::string& spec) {
  std::vector<std::string> names;
  if (spec == "bookmarks") {
    const nlohmann::json marks = bookmarksOf(sceneFile);
    for (int slot = 1; slot <= 9; ++slot)
      if (marks.contains(std::to_string(slot))) names.push_back(fmt::format("bookmark{}", slot));
    if (names.empty())
      throw session::SessionError(fmt::format("no camera bookmarks saved for {} (Ctrl+1..9 in the editor saves them, in {})",
                                              sceneName(sceneFile), (configDirectory() / "settings.json").string()));
    return names;
  }
  if (spec == "scene") {
    const size_t count = sceneCameraCount(sceneFile);
    if (count == 0) throw session::SessionError(fmt::format("{} has no glTF cameras", sceneName(sceneFile)));
    for (size_t i = 0; i < count; ++i) names.push_back(fmt::format("camera{}", i));
    return names;
  }
  std::optional<size_t> count;  // parsed once, when an index needs checking
  std::optional<nlohmann::json> marks;
  std::stringstream list(spec);
  for (std::string item; std::getline(list, item, ',');) {
    if (item.empty()) continue;
    if (item[0] == 'b') {
      if (!marks) marks = bookmarksOf(sceneFile);
      const std::string slot = item.substr(1);
      if (!marks->contains(slot))
        throw session::SessionError(fmt::format("no camera bookmark {} saved for {} (Ctrl+{} in the editor saves one)", slot,
                                                sceneName(sceneFile), slot));
      names.push_back("bookmark" + slot);
    } else if (item.size() <= 6 && item.find_first_not_of("0123456789") == std::string::npos) {
      if (!count) count = sceneCameraCount(sceneFile);
      const size_t index = std::stoul(item);
      if (index >= *count)
        throw session::SessionError(fmt::format("scene {} has {} camera(s); camera {} does not exist", sceneName(sceneFile),
                                                *count, index));
      names.push_back(fmt::format("camera{}", index));
    } else {
      throw session::SessionError(fmt::format("--cameras: `{}` is not a camera index or bookmark (b1..b9)", item));
    }
  }
  if (names.empty()) throw session::SessionError(fmt::format("--cameras `{}` names no camera", spec));
  return names;
}

void useCompareCamera(session::Session& session, const std::string& name) {
  if (name.rfind("camera", 0) == 0) {
    session.useSceneCamera(std::stoul(name.substr(6)));
    return;
  }
  const std::string slot = name.substr(std::string("bookmark").size());
  const nlohmann::json marks = bookmarksOf(session.scene().path);
  if (!marks.contains(slot))
    throw session::SessionError(fmt::format("no camera bookmark {} saved for {}", slot, session.scene().name));
  CameraController camera;
  camera.reset(session.view(), session.scene().bounds.valid() ? glm::length(session.scene().bounds.size()) : 1.0);
  camera.load(marks[slot]);
  session.setView(camera.view());
}

}  // namespace tl::editor
