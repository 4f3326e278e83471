// The editor's panels, one function per concern. Tooltips state physical units.
#include "albedo_panels.h"
#include "buffer_panel.h"
#include "column_panels.h"
#include "compare_panel.h"
#include "settings_panel.h"
#include "editor_app.h"
#include "lights_panel.h"
#include "key_help.h"
#include "ui_helpers.h"
#include "session/inspection.h"
#include "session/captured_frame.h"
#include "gpu/install_paths.h"
#include "gpu/renderdoc.h"

#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/matrix_decompose.hpp>
#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <functional>
#include <cmath>
#include <cstring>

namespace tl::editor {
namespace {

bool contains(const std::string& haystack, const std::string& needle) {
  if (needle.empty()) return true;
  auto lower = [](std::string s) {
    for (auto& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
  };
  return lower(haystack).find(lower(needle)) != std::string::npos;
}

void mainMenu(EditorApp& app, bool& showHelp, bool& showBrowser) {
  if (!ImGui::BeginMainMenuBar()) return;
  if (ImGui::BeginMenu("File")) {
    if (ImGui::MenuItem("Open...", "Ctrl+O")) showBrowser = true;
    if (ImGui::BeginMenu("Open recent", !app.settings().recentScenes.empty())) {
      for (const auto& r : app.settings().recentScenes)
        if (ImGui::MenuItem(r.c_str())) app.openScene(r);
      ImGui::EndMenu();
    }
    const auto unsaved = app.unsavedWork();
    if (ImGui::MenuItem(unsaved.any() ? "Save*" : "Save", "Ctrl+S", false, app.session().hasScene())) app.saveWork();
    tooltip(unsaved.any() ? ("Unsaved: " + unsaved.describe() +
                             ".\nThe lights into the scene's glTF and all the lighting into its sidecar, the albedo overrides into\n"
                             "the database, the render settings as this scene's (the editor reapplies them when it opens it).")
                                .c_str()
                          : "Nothing unsaved");
    if (ImGui::MenuItem("Reload scene", nullptr, false, app.session().hasScene() && !app.loading())) app.reloadScene();
    tooltip("Loads the scene's file again, keeping the camera, the selection and the albedo overrides.\n"
            "Happens by itself when the file changes on disk (a re-export).");
    if (ImGui::MenuItem("Save lighting", nullptr, false, app.session().hasScene())) app.saveLighting();
    tooltip("The sun and the lights into the scene's glTF (KHR_lights_punctual, for other tools), and all the lighting\n"
            "(area and hidden lights, sky, environment map, exposure) into SCENE.lighting.json beside it,\n"
            "which the editor reads when it opens the scene and `twinlight render --lighting FILE` renders");
    ImGui::Separator();
    for (const char* ext : {".png", ".exr"}) {
      if (ImGui::MenuItem(ext[1] == 'p' ? "Save image (PNG)" : "Save image (EXR)", nullptr, false,
                          app.session().hasScene())) {
        try {
          app.saveImage(app.defaultImagePath(ext));
        } catch (const std::exception& e) {
          app.showError(e.what());
        }
      }
      tooltip(ext[1] == 'p' ? "The viewport's engine image as shown (tonemapped, sRGB) into renders/"
                            : "The viewport's engine image as scene-linear radiance before exposure (half float) into renders/");
    }
    if (ImGui::MenuItem("Capture frame", nullptr, false, app.session().hasScene()))
      app.requestFrameCapture(app.defaultCaptureFolder());
    tooltip("Writes every buffer of the next frame as EXR, with manifest.json, into captures/");
    auto& renderdoc = gpu::RenderDoc::get();
    if (ImGui::MenuItem("RenderDoc capture", "F12", false, renderdoc.attached() && app.session().hasScene()))
      app.requestRenderDocCapture();
    tooltip(renderdoc.attached() ? "Captures the next frame in RenderDoc; passes and resources carry their graph names."
                                 : ("Unavailable: " + renderdoc.unavailableReason()).c_str());
    if (ImGui::MenuItem("Close capture", nullptr, false, app.session().hasCapture())) app.session().closeCapture();
    tooltip("Back to the live frame of the scene");
    if (ImGui::MenuItem("Quit")) app.askToQuit();
    tooltip("Asks first when there is unsaved work (save, discard or stay)");
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    if (ImGui::MenuItem("Vsync", nullptr, app.settings().vsync)) app.settings().vsync = !app.settings().vsync;
    ImGui::MenuItem("Help", "F1", &showHelp);
    ImGui::MenuItem("Buffers", "F2", &app.buffersOpen());
    ImGui::MenuItem("Compare", "F3", &app.compareOpen());
    ImGui::MenuItem("Light icons and gizmo", nullptr, &app.lightOverlayOpen());
    // Redeferred shading's I-buffer resolved against white: the light without the materials.
    const bool redeferred = app.session().settings().redeferred;
    const bool lightOnly = app.pinnedPreview() == session::kIbufferLightOnly;
    if (ImGui::MenuItem("Light only", nullptr, lightOnly, redeferred))
      app.pinPreview(lightOnly ? std::string() : std::string(session::kIbufferLightOnly));
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
      ImGui::SetTooltip(redeferred ? "the light arriving at each pixel, on a white world (the I-buffer without materials)"
                                   : "needs redeferred shading: Lighting panel, `redeferred`");
    const size_t warnings = app.session().hasScene() ? app.session().scene().warnings.size() : 0;
    ImGui::MenuItem(fmt::format("Scene ({} warning{})", warnings, warnings == 1 ? "" : "s").c_str(), nullptr,
                    &app.scenePanelOpen(), app.session().hasScene());
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
      ImGui::SetTooltip("what the file uses (meshes, materials, textures by format, lights, animations, extensions),\n"
                        "what Twinlight ignores or approximates, and the importer's warnings");
    ImGui::EndMenu();
  }
  ImGui::EndMainMenuBar();
}

void viewportPanel(EditorApp& app, glm::vec2& min, glm::vec2& size, bool& hovered) {
  // Between the columns, beside the tool panels open (panel_layout.h): nothing opens over it.
  ImGui::SetNextWindowPos(app.panelLayout().viewportPos, ImGuiCond_Always);
  ImGui::SetNextWindowSize(app.panelLayout().viewportSize, ImGuiCond_Always);
  // No background: the engine's image is blitted into the window's area underneath. It stays
  // behind every other window when clicked, so a dialog over it keeps its clicks.
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0, 0));
  ImGui::Begin("Viewport", nullptr,
               ImGuiWindowFlags_NoBackground | ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse |
                   ImGuiWindowFlags_NoBringToFrontOnFocus | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                   ImGuiWindowFlags_NoCollapse);
  ImVec2 pos = ImGui::GetCursorScreenPos();
  ImVec2 avail = ImGui::GetContentRegionAvail();
  min = {pos.x, pos.y};
  size = {std::max(avail.x, 0.0f), std::max(avail.y, 0.0f)};
  ImGui::InvisibleButton("viewport.area", ImVec2(std::max(avail.x, 1.0f), std::max(avail.y, 1.0f)),
                         ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight | ImGuiButtonFlags_MouseButtonMiddle);
  hovered = ImGui::IsItemHovered() || ImGui::IsItemActive();
  trackItem("viewport");  // scripts drag in it (drag-ui viewport DX DY orbits the camera)
  if (app.overlayShown())
    drawLightOverlay(ImGui::GetWindowDrawList(), app.viewportProjection(), app.session().lighting().lights,
                     app.selectedLight(), app.activeGizmoHandle());
  if (!app.session().hasScene()) {
    ImGui::SetCursorScreenPos(ImVec2(pos.x + 20, pos.y + 20));
    ImGui::TextUnformatted("No scene. File > Open, or drop a .gltf/.glb on the window.");
  }
  ImGui::End();
  ImGui::PopStyleVar();
}

void outlinerPanel(EditorApp& app) {
  placeColumnPanel(ColumnPanel::Outliner);
  ImGui::Begin("Outliner");
  if (!ImGui::BeginTabBar("outliner tabs")) return ImGui::End();
  const bool instancesTab = ImGui::BeginTabItem("Instances");
  trackItem("outliner.instances");
  if (instancesTab) ImGui::EndTabItem();
  const bool lightsTab = ImGui::BeginTabItem("Lights", nullptr, app.takeLightsTabRequest() ? ImGuiTabItemFlags_SetSelected : 0);
  trackItem("outliner.lights");
  tooltip("The scene's lights but the sun (the Lighting panel has the sun, sky and environment)");
  if (lightsTab) {
    lightsOutlinerTab(app);
    ImGui::EndTabItem();
  }
  ImGui::EndTabBar();
  if (!instancesTab) return ImGui::End();
  static char filter[128] = "";
  ImGui::SetNextItemWidth(-1);
  ImGui::InputTextWithHint("##search", "search instances, meshes, materials", filter, sizeof filter);
  if (app.session().hasScene()) {
    const auto& s = app.session().scene();
    // Names longer than the panel scroll into view rather than being cut off.
    ImGui::BeginChild("instances", ImVec2(0, 0), false, ImGuiWindowFlags_HorizontalScrollbar);
    for (uint32_t i = 0; i < s.instances.size(); ++i) {
      const auto& inst = s.instances[i];
      const auto& mesh = s.meshes[inst.mesh];
      const auto& mat = s.materials[mesh.material];
      if (!contains(inst.name, filter) && !contains(mesh.name, filter) && !contains(mat.name, filter)) continue;
      bool selected = app.selected() == i;
      ImGui::PushID(int(i));
      if (ImGui::Selectable(inst.name.c_str(), selected)) app.select(i);
      ImGui::SameLine(170);
      ImGui::TextDisabled("%s / %s", mesh.name.c_str(), mat.name.c_str());
      ImGui::PopID();
    }
    ImGui::EndChild();
  }
  ImGui::End();
}

void inspectorContents(EditorApp& app) {
  if (lightInspector(app)) return;
  if (!app.session().hasScene() || !app.selected() || *app.selected() >= app.session().scene().instances.size()) {
    ImGui::TextDisabled("Click an instance or a light in the viewport or the outliner.");
    return;
  }
  const auto& s = app.session().scene();
  const auto& inst = s.instances[*app.selected()];
  const auto& mesh = s.meshes[inst.mesh];
  const auto& mat = s.materials[mesh.material];
  ImGui::Text("%s", inst.name.c_str());
  ImGui::Separator();
  ImGui::Text("Mesh      %s", mesh.name.c_str());
  ImGui::Text("          %zu triangles, %zu vertices", mesh.indices.size() / 3, mesh.vertices.size());
  ImGui::Text("Material  %s", mat.name.c_str());
  ImGui::ColorButton("##base", ImVec4(mat.baseColorFactor.r, mat.baseColorFactor.g, mat.baseColorFactor.b, 1.0f));
  ImGui::SameLine();
  ImGui::Text("base colour %.3f %.3f %.3f", mat.baseColorFactor.r, mat.baseColorFactor.g, mat.baseColorFactor.b);
  ImGui::Text("metallic %.2f  roughness %.2f%s", mat.metallic, mat.roughness, mat.baseColorTexture ? "  (textured)" : "");
  if (glm::length(mat.emissiveFactor) > 0.0f)
    ImGui::Text("emissive %.2f %.2f %.2f x %.1f", mat.emissiveFactor.r, mat.emissiveFactor.g, mat.emissiveFactor.b,
                mat.emissiveStrength);
  ImGui::Separator();
  // decompose() leaves its outputs alone for a degenerate matrix: start from identity.
  glm::dvec3 scale(1.0), translation(0.0), skew(0.0);
  glm::dquat rotation(1.0, 0.0, 0.0, 0.0);
  glm::dvec4 perspective(0.0, 0.0, 0.0, 1.0);
  glm::decompose(inst.transform, scale, rotation, translation, skew, perspective);
  glm::dvec3 euler = glm::degrees(glm::eulerAngles(rotation));
  ImGui::Text("Position  %.3f %.3f %.3f m", translation.x, translation.y, translation.z);
  ImGui::Text("Rotation  %.1f %.1f %.1f deg", euler.x, euler.y, euler.z);
  ImGui::Text("Scale     %.3f %.3f %.3f", scale.x, scale.y, scale.z);
  const auto& b = inst.worldBounds;
  ImGui::Text("Bounds    %.2f %.2f %.2f", b.min.x, b.min.y, b.min.z);
  ImGui::Text("       .. %.2f %.2f %.2f m", b.max.x, b.max.y, b.max.z);
  if (ImGui::Button("Focus (F)")) app.focusSelection();
  ImGui::Separator();
  albedoInspectorSection(app, *app.selected());
}

void inspectorPanel(EditorApp& app) {
  placeColumnPanel(ColumnPanel::Inspector);
  ImGui::Begin("Inspector");
  // Its lines wrap at the panel's edge: a long mesh or material name is read, not cut off.
  ImGui::PushTextWrapPos(0.0f);
  inspectorContents(app);
  ImGui::PopTextWrapPos();
  ImGui::End();
}

void lightingPanel(EditorApp& app) {
  placeColumnPanel(ColumnPanel::Lighting);
  ImGui::Begin("Lighting");
  // Widgets leave room on their right for the longest label ("Sun irradiance", "Voxels per
  // side"), so no label is cut off at the panel's default width.
  ImGui::PushItemWidth(-(ImGui::CalcTextSize("Voxels per side").x + 2.0f * ImGui::GetStyle().ItemInnerSpacing.x));
  auto& session = app.session();
  ImGui::TextUnformatted("Lighting path");
  for (const auto& p : session.paths()) {
    ImGui::BeginDisabled(!p.available);
    if (ImGui::RadioButton(p.name.c_str(), session.path() == p.name)) app.setPath(p.name);
    ImGui::EndDisabled();
    tooltip(p.available ? p.description.c_str() : ("unavailable: " + p.unavailableReason).c_str());
  }
  if (!session.device().rayTracing().pipeline) {
    ImGui::TextDisabled("ray tracing: unavailable");
    tooltip(session.device().rayTracing().unavailableReason.c_str());
  }
  if (!session.hasScene()) {
    ImGui::PopItemWidth();
    ImGui::End();
    return;
  }
  ImGui::Separator();
  session::Lighting l = session.lighting();
  glm::dvec3 toSun = -glm::normalize(l.sunDirection);
  float elevation = float(glm::degrees(std::asin(std::clamp(toSun.y, -1.0, 1.0))));
  float azimuth = float(glm::degrees(std::atan2(toSun.x, toSun.z)));
  bool changed = false;
  changed |= ImGui::SliderFloat("Sun azimuth", &azimuth, -180.0f, 180.0f, "%.1f deg");
  tooltip("Compass direction the sunlight comes from, degrees from +Z towards +X");
  changed |= ImGui::SliderFloat("Sun elevation", &elevation, -10.0f, 90.0f, "%.1f deg");
  tooltip("Height of the sun above the horizon, degrees");
  float sunE = std::max({l.sunIrradiance.r, l.sunIrradiance.g, l.sunIrradiance.b});
  glm::vec3 sunColor = sunE > 0.0f ? l.sunIrradiance / sunE : glm::vec3(1.0f);
  changed |= ImGui::DragFloat("Sun irradiance", &sunE, 0.1f, 0.0f, 1000.0f, "%.2f W/m2");
  tooltip("Irradiance E on a surface facing the sun; a white Lambertian surface facing it shows E/pi");
  changed |= ImGui::ColorEdit3("Sun colour", &sunColor.x);
  float sunSize = glm::degrees(l.sunAngularRadius);
  if (ImGui::SliderFloat("Sun size", &sunSize, 0.05f, 5.0f, "%.2f deg", ImGuiSliderFlags_Logarithmic))
    l.sunAngularRadius = glm::radians(sunSize), changed = true;
  tooltip("Angular radius of the sun (the real one: 0.27 deg): sets the width of soft shadows (PCSS)");
  float skyL = std::max({l.skyRadiance.r, l.skyRadiance.g, l.skyRadiance.b});
  glm::vec3 skyColor = skyL > 0.0f ? l.skyRadiance / skyL : glm::vec3(1.0f);
  changed |= ImGui::DragFloat("Sky radiance", &skyL, 0.01f, 0.0f, 100.0f, "%.3f W/m2/sr");
  tooltip("Uniform radiance L of the sky; an unoccluded white surface under it shows L");
  changed |= ImGui::ColorEdit3("Sky colour", &skyColor.x);
  bool autoExposure = !l.exposureEv.has_value();
  if (ImGui::Checkbox("Auto exposure", &autoExposure)) {
    l.exposureEv = autoExposure ? std::nullopt : std::optional<float>(session.exposureEv());
    changed = true;
  }
  tooltip("Auto: a white surface lit by this sun and sky maps to 1.0 before tonemapping");
  float ev = session.exposureEv();
  ImGui::BeginDisabled(autoExposure);
  if (ImGui::SliderFloat("Exposure", &ev, -10.0f, 16.0f, "%.2f EV")) l.exposureEv = ev, changed = true;
  ImGui::EndDisabled();
  tooltip("Radiance is multiplied by 2^-EV before the ACES tonemap");
  if (changed) {
    double el = glm::radians(double(elevation)), az = glm::radians(double(azimuth));
    toSun = {std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az)};
    l.sunDirection = -toSun;
    l.sunIrradiance = sunColor * sunE;
    l.skyRadiance = skyColor * skyL;
    session.setLighting(l);
  }
  environmentSection(app);
  if (session.animated()) {
    ImGui::Separator();
    ImGui::Checkbox("Play animation", &app.playing());
    tooltip("Morph-target animations of the scene (deforming meshes), looping");
    float t = float(session.animationTime());
    if (ImGui::SliderFloat("Time", &t, 0.0f, float(session.scene().animationSeconds), "%.2f s"))
      session.setAnimationTime(t);
  }
  settingsSection(app);
  ImGui::Separator();
  ImGui::SliderFloat("Render scale", &app.settings().renderScale, 0.1f, 1.0f, "%.2f");
  tooltip("Engine resolution relative to the viewport panel; lower keeps software rendering interactive");
  ImGui::PopItemWidth();
  ImGui::End();
}

void timingPanel(EditorApp& app) {
  placeColumnPanel(ColumnPanel::Timing);
  ImGui::Begin("Timing");
  auto& session = app.session();
  std::vector<graph::PassTiming> passes =
      session.hasScene() || session.hasCapture() ? session.timings() : std::vector<graph::PassTiming>{};
  double total = 0.0, worst = 1e-6;
  for (auto& p : passes) total += p.gpuMs, worst = std::max(worst, p.gpuMs);
  std::sort(passes.begin(), passes.end(), [](auto& a, auto& b) { return a.gpuMs > b.gpuMs; });
  ImGui::Text("GPU frame %.2f ms", total);
  std::string hoveredOutput;
  for (const auto& p : passes) {
    char label[96];
    std::snprintf(label, sizeof label, "%-14s %6.2f ms", p.pass.c_str(), p.gpuMs);
    ImGui::ProgressBar(float(p.gpuMs / worst), ImVec2(-1, 0), label);
    if (ImGui::IsItemHovered()) {
      // Hovering a pass shows its first output in the viewport.
      for (const auto& r : session.resources())
        if (r.writer == p.pass && r.desc.type == graph::ResourceType::Image && r.desc.extent.depth == 1) {
          hoveredOutput = r.name;
          break;
        }
      ImGui::SetTooltip("%s%s", p.pass.c_str(), hoveredOutput.empty() ? "" : (" -> " + hoveredOutput).c_str());
    }
  }
  app.previewResource(hoveredOutput == "display.ldr" ? "" : hoveredOutput);
  ImGui::Separator();
  // The UI loop's passes (what input waits for), not the window's redraws: a pass that
  // changes nothing on screen is not drawn again (window_redraw.h).
  const auto& figures = app.shownFigures();
  ImGui::Text("UI loop %.1f passes/s, window drawn %.1f/s", figures.uiFps, figures.presentedFps);
  tooltip("Every pass of the UI loop takes the input and runs the panels; the window is drawn only when what it shows "
          "changed. The graph: each pass's time in ms.");
  if (!figures.passMs.empty())
    ImGui::PlotLines("##history", figures.passMs.data(), int(figures.passMs.size()), 0, nullptr, 0.0f,
                     *std::max_element(figures.passMs.begin(), figures.passMs.end()) * 1.2f,
                     ImVec2(ImGui::GetContentRegionAvail().x, 80));
  ImGui::End();
}

void statusBar(EditorApp& app) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(0, display.y - 24));
  ImGui::SetNextWindowSize(ImVec2(display.x, 24));
  ImGui::Begin("##status", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
  auto& s = app.session();
  const auto& compare = app.compareView();
  const std::string path = compare ? "compare " + compare->left + " | " + compare->right : "path " + s.path();
  // The interface and the engine run at their own rates: both are shown, with the age of the
  // engine frame on screen (how far behind the input it is).
  // (Refreshed a few times a second: window_redraw.h.)
  const auto& figures = app.shownFigures();
  ImGui::Text("%s  |  render %ux%u (scale %.2f)  |  UI %.0f fps, engine %.1f fps, frame %.0f ms old  |  %s  |  %s%s%s",
              s.device().name().c_str(), s.settings().width, s.settings().height, app.settings().renderScale, figures.uiFps,
              figures.engineFps, figures.frameAgeMs, path.c_str(),
              s.hasCapture()  ? ("capture " + s.capture()->dir().string() + " (File > Close capture)").c_str()
              : s.hasScene() ? s.scene().name.c_str()
                             : "no scene",
              app.shaderStatus().empty() ? "" : "  |  shaders: ",
              app.shaderStatus().c_str());
  // The latest confirmation or note (a capture written, a fallback made) for a few seconds.
  if (const EditorApp::Notice* notice = app.recentNotice()) {
    ImGui::SameLine();
    ImGui::TextColored(ImVec4(0.55f, 0.85f, 0.55f, 1.0f), "  |  %s", notice->text.c_str());
  }
  ImGui::End();
}

// Compile and pipeline errors of hot-reloaded shaders, with file and line, until fixed; the
// last good pipelines keep rendering meanwhile.
void shaderErrorWindow(EditorApp& app) {
  if (!app.shaderReloader()) return;
  const std::vector<std::string> errors = app.shaderReloader()->errors();
  if (errors.empty()) return;
  ImGui::SetNextWindowPos(app.panelLayout().shaderErrorsPos, ImGuiCond_Always);
  ImGui::SetNextWindowSize(app.panelLayout().shaderErrorsSize, ImGuiCond_Always);
  ImGui::Begin("Shader errors");
  ImGui::TextDisabled("The last good shaders keep running. Fix and save: the next poll recompiles.");
  for (const std::string& e : errors) ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", e.c_str());
  ImGui::End();
}

// Every key and mouse action the editor knows, grouped; the file browser's keys with it.
void helpWindow(const PanelLayout& layout, bool& open) {
  if (!open) return;
  placeToolPanel(layout, ToolPanel::Help);
  ImGui::Begin("Help", &open);
  // One table per section of editor/key_help.cpp (a test checks it names every key handled).
  const auto rows = keyHelp();
  for (size_t first = 0; first < rows.size();) {
    size_t end = first;
    while (end < rows.size() && std::strcmp(rows[end].section, rows[first].section) == 0) ++end;
    ImGui::TextDisabled("%s", rows[first].section);
    // The keys as wide as the widest, the action wrapped in what is left: nothing cut off.
    if (ImGui::BeginTable(rows[first].section, 2, ImGuiTableFlags_SizingFixedFit)) {
      ImGui::TableSetupColumn("keys", ImGuiTableColumnFlags_WidthFixed);
      ImGui::TableSetupColumn("action", ImGuiTableColumnFlags_WidthStretch);
      for (size_t i = first; i < end; ++i) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(rows[i].keys);
        ImGui::TableNextColumn();
        ImGui::TextWrapped("%s", rows[i].action);
      }
      ImGui::EndTable();
    }
    first = end;
  }
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextDisabled("Scenes can also be dropped onto the window; a scene reloads when its file changes on disk.");
  ImGui::PopTextWrapPos();
  trackItem("help.text");
  ImGui::End();
}

void fileBrowser(EditorApp& app, bool& open, std::filesystem::path& dir) {
  if (!open) return;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f - 280, display.y * 0.5f - 230), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(560, 460), ImGuiCond_FirstUseEver);
  ImGui::Begin("Open scene or capture", &open);
  // A typed path: a folder goes there, a scene or a capture (its folder or manifest.json) opens.
  static char typed[1024] = "";
  static std::string pathError;
  ImGui::SetNextItemWidth(-60);
  const bool entered = ImGui::InputTextWithHint("##path", "type a path, Enter", typed, sizeof typed,
                                                ImGuiInputTextFlags_EnterReturnsTrue);
  trackItem("browser.path");
  ImGui::SameLine();
  if (entered || ImGui::Button("Go")) {
    std::filesystem::path p = typed;
    std::error_code ec;
    pathError.clear();
    if (std::filesystem::is_directory(p, ec) && std::filesystem::exists(p / "manifest.json", ec)) {
      app.openCapture(p), open = false;
    } else if (std::filesystem::is_directory(p, ec)) {
      dir = std::filesystem::absolute(p, ec);
    } else if (p.filename() == "manifest.json" && std::filesystem::exists(p, ec)) {
      app.openCapture(p.parent_path()), open = false;
    } else if (std::filesystem::exists(p, ec)) {
      app.openScene(p), open = false;  // a file that is no scene is refused by the loader, with its reason
    } else {
      pathError = fmt::format("{}: no such file or folder", p.string());
    }
    if (!open) typed[0] = 0;
  }
  if (!pathError.empty()) ImGui::TextWrapped("%s", pathError.c_str());
  ImGui::TextWrapped("%s", dir.string().c_str());
  if (ImGui::Button("Up") && dir.has_parent_path()) dir = dir.parent_path();
  ImGui::SameLine();
  if (ImGui::Button("Project content")) dir = gpu::contentDirectory();
  ImGui::SameLine();
  static char filter[128] = "";
  ImGui::SetNextItemWidth(-1);
  ImGui::InputTextWithHint("##filter", "filter by name", filter, sizeof filter);
  trackItem("browser.filter");
  auto passes = [&](const std::string& name) {
    std::string a = name, b = filter;
    for (auto& c : a) c = char(std::tolower(static_cast<unsigned char>(c)));
    for (auto& c : b) c = char(std::tolower(static_cast<unsigned char>(c)));
    return a.find(b) != std::string::npos;
  };
  ImGui::BeginChild("files");
  std::error_code ec;
  std::vector<std::filesystem::directory_entry> entries;
  for (auto& e : std::filesystem::directory_iterator(dir, ec)) entries.push_back(e);
  std::sort(entries.begin(), entries.end(), [](auto& a, auto& b) { return a.path().filename() < b.path().filename(); });
  for (auto& e : entries) {
    std::string name = e.path().filename().string();
    if (!passes(name)) continue;
    if (e.is_directory(ec)) {
      if (name[0] != '.' && ImGui::Selectable(("[dir] " + name).c_str())) dir = e.path();
    } else {
      std::string ext = e.path().extension().string();
      if (name == "manifest.json") {  // a capture: its buffers, without the scene
        if (ImGui::Selectable("manifest.json (open this capture)", false, ImGuiSelectableFlags_AllowDoubleClick) &&
            ImGui::IsMouseDoubleClicked(0)) {
          app.openCapture(e.path().parent_path());
          open = false;
        }
        continue;
      }
      if (ext != ".gltf" && ext != ".glb") continue;
      if (ImGui::Selectable(name.c_str(), false, ImGuiSelectableFlags_AllowDoubleClick) && ImGui::IsMouseDoubleClicked(0)) {
        app.openScene(e.path());
        open = false;
      }
    }
  }
  ImGui::EndChild();
  ImGui::End();
}

void loadingPopup(EditorApp& app) {
  if (app.loading()) ImGui::OpenPopup("Loading");
  if (ImGui::BeginPopupModal("Loading", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    if (!app.loading()) {
      ImGui::CloseCurrentPopup();
    } else {
      ImGui::TextUnformatted("Loading the scene...");
      float t = float(ImGui::GetTime());
      ImGui::ProgressBar(std::fmod(t * 0.5f, 1.0f), ImVec2(260, 0), "");  // parse progress is not granular
      if (ImGui::Button("Cancel")) app.cancelLoad();
    }
    ImGui::EndPopup();
  }
}

// A question that needs an answer (unsaved work, a recovery), as a modal window: opened when no
// other modal window is (an error first), closed when the question is gone.
void questionPopup(const char* id, bool asked, const std::function<void()>& body) {
  if (asked && !ImGui::IsPopupOpen(id) && !ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId)) ImGui::OpenPopup(id);
  if (!ImGui::BeginPopupModal(id, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  if (!asked) ImGui::CloseCurrentPopup();
  else body();
  ImGui::EndPopup();
}

void unsavedWorkPopup(EditorApp& app) {
  const auto& q = app.unsavedQuestion();
  questionPopup("Unsaved work", q.has_value(), [&] {
    ImGui::TextUnformatted(q->text.c_str());
    ImGui::Separator();
    std::optional<EditorApp::Answer> a;
    if (ImGui::Button("Save")) a = EditorApp::Answer::Save;
    trackItem("unsaved.save");
    tooltip("File > Save, then go on");
    ImGui::SameLine();
    if (ImGui::Button("Discard")) a = EditorApp::Answer::Discard;
    trackItem("unsaved.discard");
    tooltip("Lose the unsaved work and go on");
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) a = EditorApp::Answer::Cancel;
    trackItem("unsaved.cancel");
    tooltip("Stay: nothing closes");
    if (a) app.answer(*a), ImGui::CloseCurrentPopup();
  });
}

void recoveryPopup(EditorApp& app) {
  const auto& offer = app.recoveryOffer();
  questionPopup("Recover unsaved work", offer.has_value(), [&] {
    ImGui::TextUnformatted(offer->text.c_str());
    ImGui::Separator();
    std::optional<bool> recover;
    if (ImGui::Button("Recover")) recover = true;
    trackItem("recovery.recover");
    tooltip("Apply it as unsaved edits (File > Save keeps them, Ctrl+Z takes them back)");
    ImGui::SameLine();
    if (ImGui::Button("Discard")) recover = false;
    trackItem("recovery.discard");
    tooltip("Delete the recovery file: the scene stays as its files hold it");
    if (recover) app.answerRecovery(*recover), ImGui::CloseCurrentPopup();
  });
}

void errorPopup(std::string& error) {
  if (!error.empty()) ImGui::OpenPopup("Error");
  if (ImGui::BeginPopupModal("Error", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::PushTextWrapPos(520);
    ImGui::TextUnformatted(error.c_str());
    ImGui::PopTextWrapPos();
    if (ImGui::Button("OK")) {
      error.clear();
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }
}

}  // namespace

// The scene report (scene::sceneReport, what `twinlight info --scene` prints: what the file uses,
// counted, and each feature ignored or approximated) and what the importer said about the scene
// (Scene::warnings: the missing texture, the extension not applied), where the terminal is not
// in view.
void scenePanel(EditorApp& app) {
  if (!app.scenePanelOpen() || !app.session().hasScene()) return;
  const scene::Scene& s = app.session().scene();
  placeToolPanel(app.panelLayout(), ToolPanel::Scene);
  if (!ImGui::Begin("Scene", &app.scenePanelOpen())) {
    ImGui::End();
    return;
  }
  ImGui::TextUnformatted(s.path.filename().string().c_str());
  ImGui::Separator();
  // The report's "ignored:" lines are where the image differs from the file.
  for (const std::string& line : app.sceneReport()) ImGui::TextWrapped("%s", line.c_str());
  ImGui::Separator();
  // Each ignored feature is also a warning: the list opens by itself only for other warnings
  // (a missing texture, a value clamped).
  const ImGuiTreeNodeFlags open = s.warnings.size() > s.ignored.size() ? ImGuiTreeNodeFlags_DefaultOpen : 0;
  const std::string header = fmt::format("{} warning{} from the importer (also on the terminal)###warnings", s.warnings.size(),
                                         s.warnings.size() == 1 ? "" : "s");
  if (!ImGui::CollapsingHeader(header.c_str(), open)) {
    ImGui::End();
    return;
  }
  for (const std::string& line : s.warnings) {
    ImGui::Bullet();
    ImGui::SameLine();
    ImGui::TextWrapped("%s", line.c_str());
  }
  ImGui::End();
}

void drawPanels(EditorApp& app) {
  beginTrackedFrame();
  beginColumnLayout();
  {
    std::array<bool, size_t(ToolPanel::Count)> tools{};
    tools[size_t(ToolPanel::Scene)] = app.scenePanelOpen() && app.session().hasScene();
    tools[size_t(ToolPanel::Buffers)] = app.buffersOpen();
    tools[size_t(ToolPanel::Compare)] = app.compareOpen();
    tools[size_t(ToolPanel::Help)] = app.showHelp_;
    const bool shaderErrors = app.shaderReloader() && !app.shaderReloader()->errors().empty();
    app.layout_ = panelLayout(ImGui::GetIO().DisplaySize, tools, shaderErrors);
  }
  mainMenu(app, app.showHelp_, app.showBrowser_);
  viewportPanel(app, app.viewportMin_, app.viewportSize_, app.viewportHovered_);
  outlinerPanel(app);
  inspectorPanel(app);
  lightingPanel(app);
  timingPanel(app);
  albedoPanel(app);
  comparePanel(app);
  compareViewportOverlay(app);
  buffersPanel(app, app.buffersOpen());
  scenePanel(app);
  statusBar(app);
  shaderErrorWindow(app);
  helpWindow(app.layout_, app.showHelp_);
  fileBrowser(app, app.showBrowser_, app.browserDir_);
  loadingPopup(app);
  errorPopup(app.error_);
  unsavedWorkPopup(app);
  recoveryPopup(app);
  checkWindowsFit();
}

}  // namespace tl::editor
