#include "compare_cameras.h"

#include "camera_controller.h"
#include "settings.h"

#include <fmt/format.h>

#include <filesystem>
#include <sstream>

namespace tl::editor {
namespace {

session::View bookmarkView(session::Session& session, const nlohmann::json& saved) {
  CameraController camera;
  camera.reset(session.view(), session.scene().bounds.valid() ? glm::length(session.scene().bounds.size()) : 1.0);
  camera.load(saved);
  return camera.view();
}

}  // namespace

std::vector<NamedView> resolveCompareCameras(session::Session& session, const std::string& spec) {
  const std::string sceneKey = std::filesystem::absolute(session.scene().path).string();
  const Settings settings = loadSettings();
  const nlohmann::json marks =
      settings.bookmarks.contains(sceneKey) ? settings.bookmarks[sceneKey] : nlohmann::json::object();
  std::vector<NamedView> views;
  auto sceneCamera = [&](size_t i) {
    session.useSceneCamera(i);  // throws with the range when out of it
    views.push_back({fmt::format("camera{}", i), session.view()});
  };
  auto bookmark = [&](const std::string& slot) {
    if (!marks.contains(slot))
      throw session::SessionError(fmt::format("no camera bookmark {} saved for {} (Ctrl+{} in the editor saves one)", slot,
                                              session.scene().name, slot));
    views.push_back({"bookmark" + slot, bookmarkView(session, marks[slot])});
  };
  if (spec == "bookmarks") {
    for (int slot = 1; slot <= 9; ++slot)
      if (marks.contains(std::to_string(slot))) bookmark(std::to_string(slot));
    if (views.empty())
      throw session::SessionError(fmt::format("no camera bookmarks saved for {} (Ctrl+1..9 in the editor saves them, in {})",
                                              session.scene().name, (configDirectory() / "settings.json").string()));
  } else if (spec == "scene") {
    if (session.scene().cameras.empty()) throw session::SessionError(fmt::format("{} has no glTF cameras", session.scene().name));
    for (size_t i = 0; i < session.scene().cameras.size(); ++i) sceneCamera(i);
  } else {
    std::stringstream list(spec);
    for (std::string item; std::getline(list, item, ',');) {
      if (item.empty()) continue;
      if (item[0] == 'b') bookmark(item.substr(1));
      else if (item.find_first_not_of("0123456789") == std::string::npos) sceneCamera(std::stoul(item));
      else throw session::SessionError(fmt::format("--cameras: `{}` is not a camera index or bookmark (b1..b9)", item));
    }
  }
  return views;
}

}  // namespace tl::editor
