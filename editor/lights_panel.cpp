#include "lights_panel.h"

#include "editor_app.h"
#include "light_gizmo.h"
#include "ui_helpers.h"

#include "scene/color_temperature.h"
#include "scene/environment_map.h"
#include "scene/input_limits.h"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace tl::editor {
namespace {

using scene::LightType;

constexpr LightType kAddable[] = {LightType::Point, LightType::Spot, LightType::Directional,
                                  LightType::Rect, LightType::Disk, LightType::Tube};

const char* addTooltip(LightType t) {
  switch (t) {
    case LightType::Point: return "a bulb: shines all round (intensity in candela)";
    case LightType::Spot: return "a spotlight: a cone with a soft edge between its inner and outer angle (candela)";
    case LightType::Directional: return "a second sun: parallel light from one direction (illuminance in lux)";
    case LightType::Rect: return "a rectangular panel emitting from its front (radiance in nits, cd/m2)";
    case LightType::Disk: return "a round panel emitting from its front (nits)";
    case LightType::Tube: return "a tube light, emitting all round its side (nits)";
  }
  return "";
}

// Direction as compass azimuth and elevation (degrees) of where the light shines to.
bool directionWidgets(glm::dvec3& direction) {
  const glm::dvec3 d = glm::normalize(direction);
  float elevation = float(glm::degrees(std::asin(std::clamp(d.y, -1.0, 1.0))));
  float azimuth = float(glm::degrees(std::atan2(d.x, d.z)));
  bool changed = ImGui::SliderFloat("Aim azimuth", &azimuth, -180.0f, 180.0f, "%.1f deg");
  tooltip("Compass direction the light shines towards, degrees from +Z towards +X (or drag the gizmo's yellow knob)");
  changed |= ImGui::SliderFloat("Aim elevation", &elevation, -90.0f, 90.0f, "%.1f deg");
  tooltip("Up or down the light shines, degrees (-90: straight down)");
  if (changed) {
    const double el = glm::radians(double(elevation)), az = glm::radians(double(azimuth));
    direction = {std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az)};
  }
  return changed;
}

// A length in the scene's units, dragged by a share of its own size (or of the scene's, from
// nothing) and bounded by the scene's size: the same feel in a millimetre model and a city.
bool metres(const char* label, float& value, const char* help, float sceneSize) {
  const float speed = 0.01f * std::max(std::abs(value), 1e-3f * sceneSize);
  const bool changed = ImGui::DragFloat(label, &value, speed, 1e-6f * sceneSize, 100.0f * sceneSize, "%.4g m",
                                        ImGuiSliderFlags_AlwaysClamp | ImGuiSliderFlags_Logarithmic);
  tooltip(help);
  return changed;
}

// The selected light's properties; returns whether one changed. `sceneSize`: the diagonal of
// the scene's bounds, which sets the lengths' drag speeds, bounds and new defaults.
bool lightProperties(scene::Light& l, float sceneSize) {
  bool changed = false;
  char name[128];
  std::snprintf(name, sizeof name, "%s", l.name.c_str());
  if (ImGui::InputText("Name", name, sizeof name)) l.name = name, changed = true;
  tooltip("Saved as the light's name in the glTF (KHR_lights_punctual) and the lighting file");
  ImGui::Text("Type      %s", scene::lightTypeName(l.type));
  changed |= ImGui::ColorEdit3("Colour", &l.color.x, ImGuiColorEditFlags_Float);
  tooltip("Linear RGB multiplying the intensity");
  static float kelvin = 6500.0f;
  if (ImGui::DragFloat("Temperature", &kelvin, 10.0f, float(scene::kMinColorTemperature), 20000.0f, "%.0f K",
                       ImGuiSliderFlags_AlwaysClamp))
    l.color = scene::colorTemperatureToRgb(double(kelvin)), changed = true;
  tooltip("Sets the colour to a black body's at this temperature (2700 K: a warm bulb; 6500 K: daylight)");
  const char* unit = lightIntensityUnit(l.type);
  const std::string format = fmt::format("%.2f {}", unit);
  changed |= ImGui::DragFloat("Intensity", &l.intensity, std::max(0.01f, 0.01f * l.intensity), 0.0f, 1e7f, format.c_str(),
                              ImGuiSliderFlags_AlwaysClamp | ImGuiSliderFlags_Logarithmic);
  tooltip(l.type == LightType::Directional ? "Illuminance in lux on a surface facing the light (the real sun: about 100000)"
          : scene::isAreaLight(l.type)     ? "Radiance in nits (cd/m2) of the emitting face (an LED panel: a few thousand)"
                                           : "Luminous intensity in candela (a 100 W bulb: about 140)");
  if (l.type != LightType::Directional) {
    glm::vec3 p(l.position);
    const float limit = float(scene::InputLimits::kMaxCoordinate);
    if (ImGui::DragFloat3("Position", &p.x, 1e-3f * sceneSize, -limit, limit, "%.4g m", ImGuiSliderFlags_AlwaysClamp))
      l.position = glm::dvec3(p), changed = true;
    tooltip("World position in metres, y up (or drag the gizmo's arrows)");
  }
  if (l.type != LightType::Point) changed |= directionWidgets(l.direction);
  if (l.type == LightType::Point || l.type == LightType::Spot) {
    bool limited = l.range.has_value();
    // Limited, it starts at half the scene's size: the light fades out inside the scene.
    if (ImGui::Checkbox("Limited range", &limited)) l.range = limited ? std::optional<float>(0.5f * sceneSize) : std::nullopt, changed = true;
    tooltip("KHR_lights_punctual's range: the light fades to nothing at this distance (off: the inverse square law alone)");
    if (l.range) changed |= metres("Range", *l.range, "Distance at which the light has faded to nothing", sceneSize);
  }
  if (l.type == LightType::Spot) {
    float inner = glm::degrees(l.innerConeAngle), outer = glm::degrees(l.outerConeAngle);
    bool cones = ImGui::SliderFloat("Inner cone", &inner, 0.0f, 89.0f, "%.1f deg", ImGuiSliderFlags_AlwaysClamp);
    tooltip("Half-angle of the fully lit core");
    cones |= ImGui::SliderFloat("Outer cone", &outer, 0.5f, 90.0f, "%.1f deg", ImGuiSliderFlags_AlwaysClamp);
    tooltip("Half-angle where the light has faded to nothing");
    if (cones) {
      // KHR_lights_punctual: 0 <= inner < outer <= 90 degrees.
      outer = std::max(outer, 0.5f);
      inner = std::min(inner, outer - 0.25f);
      l.innerConeAngle = glm::radians(std::max(inner, 0.0f));
      l.outerConeAngle = glm::radians(outer);
      changed = true;
    }
  }
  if (l.type == LightType::Rect) {
    changed |= metres("Width", l.width, "Size along the panel's width axis", sceneSize);
    changed |= metres("Height", l.height, "Size across it", sceneSize);
  }
  if (l.type == LightType::Disk || l.type == LightType::Tube) changed |= metres("Radius", l.radius, "Radius of the disk or tube", sceneSize);
  if (l.type == LightType::Tube) changed |= metres("Length", l.length, "Length of the tube along its axis (its aim)", sceneSize);
  if (l.type == LightType::Rect || l.type == LightType::Disk) {
    changed |= ImGui::Checkbox("Two-sided", &l.twoSided);
    tooltip("Emit from both faces (off: the front face alone, the side it aims at)");
  }
  return changed;
}

}  // namespace

void lightsOutlinerTab(EditorApp& app) {
  auto& session = app.session();
  if (!session.hasScene()) return;
  session::Lighting l = session.lighting();
  const std::optional<size_t> selected = app.selectedLight();
  if (ImGui::Button("Add")) ImGui::OpenPopup("add light");
  trackItem("lights.add");
  tooltip("Add a light in front of the camera");
  if (ImGui::BeginPopup("add light")) {
    for (LightType t : kAddable) {
      if (ImGui::MenuItem(scene::lightTypeName(t))) app.addLight(t);
      trackItem(fmt::format("lights.add.{}", scene::lightTypeName(t)));
      tooltip(addTooltip(t));
    }
    ImGui::EndPopup();
  }
  ImGui::SameLine();
  ImGui::BeginDisabled(!selected);
  if (ImGui::Button("Duplicate")) app.duplicateSelectedLight();
  trackItem("lights.duplicate");
  tooltip("A copy of the selected light, beside it");
  ImGui::SameLine();
  if (ImGui::Button("Delete")) app.deleteSelectedLight();
  trackItem("lights.delete");
  tooltip("Remove the selected light (Ctrl+Z brings it back)");
  ImGui::SameLine();
  if (ImGui::Button("Solo")) app.soloSelectedLight();
  trackItem("lights.solo");
  tooltip("Show the selected light alone (every other light hidden); again: show them all.\n"
          "The sun, sky and environment stay: set them in the Lighting panel");
  ImGui::EndDisabled();

  ImGui::BeginChild("light list");
  if (l.lights.empty()) ImGui::TextDisabled("no lights but the sun and sky (Lighting panel)");
  bool changed = false;
  for (size_t i = 0; i < l.lights.size(); ++i) {
    scene::Light& light = l.lights[i];
    ImGui::PushID(int(i));
    bool visible = !light.hidden;
    if (ImGui::Checkbox("##visible", &visible)) light.hidden = !visible, changed = true;
    trackItem(fmt::format("lights.visible.{}", i));
    tooltip("Shown or hidden: a hidden light is kept and saved (in the lighting file), not shaded");
    ImGui::SameLine();
    const std::string label = fmt::format("{} ({})", light.name.empty() ? "unnamed" : light.name, scene::lightTypeName(light.type));
    if (ImGui::Selectable(label.c_str(), selected && *selected == i)) app.selectLight(i);
    trackItem(fmt::format("lights.row.{}", i));
    ImGui::PopID();
  }
  ImGui::EndChild();
  if (changed) session.setLighting(l);
}

bool lightInspector(EditorApp& app) {
  auto& session = app.session();
  const std::optional<size_t> selected = app.selectedLight();
  if (!session.hasScene() || !selected || *selected >= session.lighting().lights.size()) return false;
  session::Lighting l = session.lighting();
  ImGui::Text("%s", l.lights[*selected].name.c_str());
  ImGui::Separator();
  ImGui::PushItemWidth(-ImGui::CalcTextSize("Aim elevation").x - 2.0f * ImGui::GetStyle().ItemInnerSpacing.x);
  if (lightProperties(l.lights[*selected], std::max(session.sceneSize().diagonal, 1e-6f))) session.setLighting(l);
  ImGui::PopItemWidth();
  return true;
}

void environmentSection(EditorApp& app) {
  auto& session = app.session();
  session::Lighting l = session.lighting();
  ImGui::Separator();
  ImGui::TextUnformatted("Environment");
  std::string& field = app.environmentField();
  if (field.empty() && l.environmentMap) field = l.environmentMap->path.string();
  char path[512];
  std::snprintf(path, sizeof path, "%s", field.c_str());
  if (ImGui::InputTextWithHint("Map file", "an equirectangular .exr or .hdr", path, sizeof path)) field = path;
  trackItem("environment.file");
  tooltip("Equirectangular environment map (EXR or HDR, radiance on the sky's scale) in place of the uniform sky");
  if (ImGui::Button("Load map")) app.loadEnvironmentMap(field);
  trackItem("environment.load");
  ImGui::SameLine();
  ImGui::BeginDisabled(!l.environmentMap);
  if (ImGui::Button("Uniform sky")) {
    l.environmentMap.reset();
    session.setLighting(l);
  }
  trackItem("environment.clear");
  tooltip("Back to the uniform sky of the Sky radiance above");
  bool changed = false;
  float rotation = glm::degrees(l.environmentRotation);
  if (ImGui::SliderFloat("Map rotation", &rotation, -180.0f, 180.0f, "%.1f deg"))
    l.environmentRotation = glm::radians(rotation), changed = true;
  tooltip("Turns the map about +Y, counter-clockwise seen from above");
  changed |= ImGui::DragFloat("Map intensity", &l.environmentIntensity, 0.01f, 0.0f, 1e6f, "%.3f",
                              ImGuiSliderFlags_AlwaysClamp | ImGuiSliderFlags_Logarithmic);
  tooltip("Multiplies the map's radiance");
  ImGui::EndDisabled();
  if (l.environmentMap)
    ImGui::TextDisabled("%s, %ux%u", l.environmentMap->path.filename().string().c_str(), l.environmentMap->width,
                        l.environmentMap->height);
  if (const auto sun = session.environmentSun()) {
    const glm::vec3 e = session.shadedLighting().sunIrradiance;
    ImGui::TextDisabled("its sun (E %.2f, %.1f deg wide) shades as the sun", std::max({e.r, e.g, e.b}),
                        glm::degrees(2.0 * sun->angularRadius));
    tooltip("A sun found in the map is taken out of it and shaded as a directional light of its size, with shadows,\n"
            "in every path (spherical harmonics would spread it over the sky). Turning the sun above on keeps it in the map.");
  }
  if (changed) session.setLighting(l);
}

}  // namespace tl::editor
