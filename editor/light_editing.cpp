// The editor's light edits: adding, duplicating, deleting, hiding and soloing lights, dragging
// them with the viewport gizmo, the environment map, and saving it all beside the scene. Each
// edit is a lighting change of the session, which the edit history turns into an undo step.
#include "editor_app.h"

#include "scene/environment_map.h"
#include "session/lighting_file.h"

#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>

namespace tl::editor {
namespace {

// A new light of `type` placed `away` from the camera in a scene `size` across (its bounds'
// diagonal): an area light's size is a share of the scene's, and a point or spot light gives
// the illuminance at `away` that 150 cd (600 cd) give at 2 m, so it lights a millimetre model
// and a hall alike. Nits and lux do not depend on the scene's units.
scene::Light defaultLight(scene::LightType type, double away, double size) {
  scene::Light l;
  l.type = type;
  l.direction = {0.0, -1.0, 0.0};  // ceiling lights shine down
  switch (type) {
    case scene::LightType::Point: l.intensity = float(150.0 * (away / 2.0) * (away / 2.0)); break;
    case scene::LightType::Spot:
      l.intensity = float(600.0 * (away / 2.0) * (away / 2.0));
      l.innerConeAngle = glm::radians(20.0f);
      l.outerConeAngle = glm::radians(30.0f);
      break;
    case scene::LightType::Directional:
      l.intensity = 10000.0f;
      l.direction = glm::normalize(glm::dvec3(0.4, -1.0, -0.3));
      break;
    case scene::LightType::Rect:
      l.intensity = 3000.0f;
      l.width = l.height = float(0.05 * size);
      break;
    case scene::LightType::Disk:
      l.intensity = 3000.0f;
      l.radius = float(0.025 * size);
      break;
    case scene::LightType::Tube:
      l.intensity = 3000.0f;
      l.radius = float(0.002 * size);
      l.length = float(0.1 * size);
      l.direction = {1.0, 0.0, 0.0};  // a tube's axis
      break;
  }
  return l;
}

}  // namespace

void EditorApp::addLight(scene::LightType type) {
  if (!session_->hasScene()) return;
  session::Lighting l = session_->lighting();
  const session::View v = camera_.view();
  // In front of the camera, a third of the scene's size away; beside a light already there
  // (the last one added, not yet moved) rather than inside it, a quarter of that away to the
  // camera's right, so each new light can be seen and picked on its own.
  const double size = std::max(double(session_->sceneSize().diagonal), 1e-6);
  const double away = 0.3 * size;
  scene::Light light = defaultLight(type, away, size);
  light.position = v.position + glm::normalize(v.forward) * away;
  const glm::dvec3 right = glm::normalize(glm::cross(v.forward, v.up));
  const auto taken = [&](const glm::dvec3& p) {
    return std::any_of(l.lights.begin(), l.lights.end(),
                       [&](const scene::Light& o) { return glm::length(o.position - p) < 0.2 * away; });
  };
  for (int step = 0; step < 64 && taken(light.position); ++step) light.position += right * (0.25 * away);
  size_t same = 1;
  for (const auto& other : l.lights) same += other.type == type;
  light.name = fmt::format("{} {}", scene::lightTypeName(type), same);
  l.lights.push_back(light);
  session_->setLighting(l);
  selectLight(l.lights.size() - 1);
  notify(fmt::format("added {} (Lights panel; drag its arrows in the viewport to move it)", light.name));
}

void EditorApp::duplicateSelectedLight() {
  session::Lighting l = session_->lighting();
  if (!selectedLight_ || *selectedLight_ >= l.lights.size()) return;
  scene::Light copy = l.lights[*selectedLight_];
  copy.node.reset();  // a light of its own when saved
  copy.name += " copy";
  // Beside the original by a fortieth of the scene's size: apart, and still where it was put.
  copy.position += glm::dvec3(0.025 * double(session_->sceneSize().diagonal), 0.0, 0.0);
  l.lights.push_back(copy);
  session_->setLighting(l);
  selectLight(l.lights.size() - 1);
}

void EditorApp::deleteSelectedLight() {
  session::Lighting l = session_->lighting();
  if (!selectedLight_ || *selectedLight_ >= l.lights.size()) return;
  const std::string name = l.lights[*selectedLight_].name;
  l.lights.erase(l.lights.begin() + std::ptrdiff_t(*selectedLight_));
  session_->setLighting(l);
  selectedLight_.reset();
  notify(fmt::format("deleted {} (Ctrl+Z brings it back)", name));
}

void EditorApp::soloSelectedLight() {
  session::Lighting l = session_->lighting();
  if (!selectedLight_ || *selectedLight_ >= l.lights.size()) return;
  bool alone = !l.lights[*selectedLight_].hidden;
  for (size_t i = 0; i < l.lights.size(); ++i)
    if (i != *selectedLight_) alone = alone && l.lights[i].hidden;
  for (size_t i = 0; i < l.lights.size(); ++i) l.lights[i].hidden = alone ? false : i != *selectedLight_;
  session_->setLighting(l);
}

std::string EditorApp::saveLighting() {
  if (!session_->hasScene()) return {};
  try {
    session::Lighting l = session_->lighting();
    const auto saved = session::saveSceneLighting(session_->scene().path, l);
    session_->setLighting(l);  // the nodes the lights now live on (not an edit: the history ignores them)
    savedLighting_ = l;
    watchScene();              // our own write is not an export to reload
    const std::string text = fmt::format("saved {} light{} into {} and all the lighting into {}", saved.gltfLights,
                                         saved.gltfLights == 1 ? "" : "s", session_->scene().path.filename().string(),
                                         saved.sidecar.filename().string());
    notify(text);
    return text;
  } catch (const std::exception& e) {
    showError(e.what());
    return {};
  }
}

void EditorApp::loadEnvironmentMap(const std::string& file) {
  if (file.empty()) return showError("give the environment map's file (.exr or .hdr)");
  try {
    session::Lighting l = session_->lighting();
    l.environmentMap = std::make_shared<const scene::EnvironmentMap>(scene::loadEnvironmentMap(file));
    session_->setLighting(l);
    notify(fmt::format("environment map {} ({}x{})", file, l.environmentMap->width, l.environmentMap->height));
  } catch (const std::exception& e) {
    showError(e.what());
  }
}

ViewportProjection EditorApp::viewportProjection() const {
  ViewportProjection p;
  p.view = camera_.view();
  p.min = viewportMin_;
  p.size = viewportSize_;
  return p;
}

bool EditorApp::overlayShown() const {
  return showLightOverlay_ && session_->hasScene() && viewer_.resource.empty() && preview_.empty() && viewer_.zoom <= 1.0f &&
         !compareView_;
}

bool EditorApp::handleLightOverlayInput(glm::vec2 mouse) {
  if (gizmoDrag_) {
    session::Lighting l = session_->lighting();
    const ViewportProjection p = viewportProjection();
    if (gizmoDrag_->light < l.lights.size()) {
      const scene::Light moved = draggedLight(*gizmoDrag_, p, mouse);
      if (!session::sameLight(moved, l.lights[gizmoDrag_->light])) {  // a held, unmoved mouse changes nothing
        l.lights[gizmoDrag_->light] = moved;
        session_->setLighting(l);
      }
      if (!ImGui::IsMouseDown(0)) lastGizmoDrag_ = FinishedGizmoDrag{*gizmoDrag_, mouse, moved, p};
    }
    if (!ImGui::IsMouseDown(0)) gizmoDrag_.reset(), overlayPress_ = false;
    return true;
  }
  if (overlayPress_) {  // a press on an icon: its release is not a pick
    if (!ImGui::IsMouseDown(0)) overlayPress_ = false;
    return true;
  }
  if (!overlayShown() || !viewportHovered_ || !ImGui::IsMouseClicked(0)) return false;
  const ViewportProjection p = viewportProjection();
  const auto& lights = session_->lighting().lights;
  if (selectedLight_ && *selectedLight_ < lights.size()) {
    if (const auto g = gizmoGeometry(p, lights[*selectedLight_])) {
      const GizmoHandle h = gizmoHandleAt(*g, mouse);
      if (h != GizmoHandle::None) {
        gizmoDrag_ = GizmoDrag{h, *selectedLight_, lights[*selectedLight_], p.rayThrough(mouse), mouse, g->armMetres};
        overlayPress_ = true;
        return true;
      }
    }
  }
  if (const auto icon = lightIconAt(p, lights, mouse)) {
    selectLight(icon);
    overlayPress_ = true;
    return true;
  }
  return false;
}

}  // namespace tl::editor
