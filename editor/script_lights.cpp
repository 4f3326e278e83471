// Script commands on lights: dragging a viewport handle as a person does, and the
// expectations a test of light editing needs.
#include "script_commands.h"

#include "editor_app.h"
#include "ui_helpers.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>

namespace tl::editor {
namespace {

std::string describe(const scene::Light& l) {
  std::string text = fmt::format("{} ({}) at {:.3f} {:.3f} {:.3f}", l.name, scene::lightTypeName(l.type), l.position.x,
                                 l.position.y, l.position.z);
  if (l.type != scene::LightType::Point) {
    const glm::dvec3 d = glm::normalize(l.direction);
    text += fmt::format(" aim {:.3f} {:.3f} {:.3f}", d.x, d.y, d.z);
  }
  text += fmt::format(" {:g} {}", l.intensity, lightIntensityUnit(l.type));
  if (l.hidden) text += " hidden";
  return text;
}

// After a drag: the light followed the mouse. An arrow moves the light along its axis alone, as
// far on screen as the mouse went along the arrow's screen direction; the knob ends under the mouse.
std::string checkGizmoFollowed(const EditorApp::FinishedGizmoDrag& d) {
  const ViewportProjection& p = d.projection;
  const scene::Light& before = d.drag.start;
  const scene::Light& after = d.end;
  if (d.drag.handle == GizmoHandle::Aim) {
    const auto g = gizmoGeometry(p, after);
    if (!g || !g->aimKnob) return "the aimed light has no knob on screen";
    const float off = glm::length(*g->aimKnob - d.endMouse);
    // Beyond the sphere's outline the knob stays on the outline, towards the mouse.
    const glm::vec2 toKnob = *g->aimKnob - g->centre, toMouse = d.endMouse - g->centre;
    const bool outside = glm::length(toMouse) > glm::length(toKnob) + 3.0f;
    if (outside && glm::dot(glm::normalize(toKnob), glm::normalize(toMouse)) < std::cos(glm::radians(2.0f)))
      return fmt::format("the knob ended off the line from the light to the mouse ({:.1f} px from it)", off);
    if (!outside && off > 3.0f) return fmt::format("the knob ended {:.1f} px from the mouse", off);
    if (glm::dot(glm::normalize(before.direction), after.direction) > 1.0 - 1e-6) return "the light's aim did not change";
    fmt::print("script: the knob ended {:.2f} px from the mouse; aim {:.3f} {:.3f} {:.3f}\n", off, after.direction.x,
               after.direction.y, after.direction.z);
    return {};
  }
  const int axis = int(d.drag.handle) - int(GizmoHandle::MoveX);
  for (int c = 0; c < 3; ++c)
    if (c != axis && after.position[c] != before.position[c])
      return fmt::format("dragging axis {} changed coordinate {} ({} -> {})", "xyz"[axis], "xyz"[c], before.position[c],
                         after.position[c]);
  if (std::abs(after.position[axis] - before.position[axis]) < 1e-4) return "the light did not move";
  // The point of the arrow the press grabbed moved with the light; on screen it stays under the
  // mouse along the arrow's line (the mouse's offset across the line moves nothing).
  const auto grabbed = grabbedPoint(d.drag);
  if (!grabbed) return "the drag grabbed no point of its arrow";
  const glm::dvec3 moved = *grabbed + (after.position - before.position);
  const auto at = p.toWindow(moved), further = p.toWindow(moved + gizmoAxis(d.drag.handle) * (0.1 * d.drag.armMetres));
  if (!at || !further) return "the grabbed point left the screen";
  const glm::vec2 along = glm::normalize(*further - *at);
  const float off = std::abs(glm::dot(d.endMouse - *at, along));
  if (off > 2.0f) return fmt::format("the grabbed point of the arrow ended {:.1f} px from the mouse along it", off);
  fmt::print("script: the light moved {:.4f} m along {} and ended {:.2f} px from the drag's point\n",
             after.position[axis] - before.position[axis], "xyz"[axis], off);
  return {};
}

// drag-ui NAME DX DY [U V]: press on a tracked control or handle (at the fraction U, V of its box;
// its centre by default), move by (DX, DY) pixels over eight frames, release.
void dragUi(EditorApp& app, ScriptState&, const std::string& arg) {
  char name[128];
  float dx = 0.0f, dy = 0.0f, u = 0.5f, v = 0.5f;
  const int read = std::sscanf(arg.c_str(), "%127s %f %f %f %f", name, &dx, &dy, &u, &v);
  if (read != 3 && read != 5) throw ScriptFailure("drag-ui needs NAME DX DY [U V]");
  if (!(u >= 0.0f && u <= 1.0f && v >= 0.0f && v <= 1.0f)) throw ScriptFailure("drag-ui's U and V are fractions from 0 to 1");
  const auto item = trackedItem(name);
  if (!item) throw ScriptFailure(fmt::format("no control `{}` on screen", name));
  const glm::vec2 from = item->min + (item->max - item->min) * glm::vec2(u, v);
  auto& in = app.input();
  in.push({InputEvent::Kind::Move, from});
  in.push({InputEvent::Kind::Frame});
  in.push({InputEvent::Kind::Button, {}, 0, true});
  constexpr int kSteps = 8;
  for (int i = 1; i <= kSteps; ++i) {
    in.push({InputEvent::Kind::Frame});
    in.push({InputEvent::Kind::Move, from + glm::vec2(dx, dy) * (float(i) / kSteps)});
  }
  in.push({InputEvent::Kind::Frame});
  in.push({InputEvent::Kind::Button, {}, 0, false});
}

void expectLights(EditorApp& app, ScriptState&, const std::string& arg) {
  const auto& lights = app.session().lighting().lights;
  const size_t want = size_t(std::max(0, std::atoi(arg.c_str())));
  for (size_t i = 0; i < lights.size(); ++i) fmt::print("script: light {}: {}\n", i, describe(lights[i]));
  if (lights.size() != want) throw ScriptFailure(fmt::format("{} lights, expected {}", lights.size(), want));
}

// expect-light I TEXT: light I's description holds TEXT.
void expectLight(EditorApp& app, ScriptState&, const std::string& arg) {
  const auto& lights = app.session().lighting().lights;
  const auto space = arg.find(' ');
  const size_t i = size_t(std::max(0, std::atoi(arg.substr(0, space).c_str())));
  const std::string text = space == std::string::npos ? "" : arg.substr(space + 1);
  if (i >= lights.size()) throw ScriptFailure(fmt::format("no light {} ({} lights)", i, lights.size()));
  const std::string d = describe(lights[i]);
  if (d.find(text) == std::string::npos) throw ScriptFailure(fmt::format("light {} is `{}`, without `{}`", i, d, text));
  fmt::print("script: light {}: {}\n", i, d);
}

// expect-lights-apart I J: lights I and J do not stand at one point (a tenth of a per cent of the
// scene's size apart at least).
void expectLightsApart(EditorApp& app, ScriptState&, const std::string& arg) {
  const auto& lights = app.session().lighting().lights;
  size_t i = 0, j = 0;
  if (std::sscanf(arg.c_str(), "%zu %zu", &i, &j) != 2) throw ScriptFailure("expect-lights-apart needs I J");
  if (i >= lights.size() || j >= lights.size()) throw ScriptFailure(fmt::format("no light {} or {} ({} lights)", i, j, lights.size()));
  const double d = glm::length(lights[i].position - lights[j].position);
  const double size = glm::length(app.session().scene().bounds.size());
  if (d < 1e-3 * size) throw ScriptFailure(fmt::format("lights {} and {} stand {:.4f} m apart: at one point", i, j, d));
  fmt::print("script: lights {} and {} stand {:.3f} m apart\n", i, j, d);
}

void expectGizmoFollowed(EditorApp& app, ScriptState&, const std::string&) {
  if (!app.lastGizmoDrag()) throw ScriptFailure("no gizmo drag has finished");
  if (const std::string failure = checkGizmoFollowed(*app.lastGizmoDrag()); !failure.empty()) throw ScriptFailure(failure);
}

void expectSelectedLight(EditorApp& app, ScriptState&, const std::string& arg) {
  const auto& lights = app.session().lighting().lights;
  const auto s = app.selectedLight();
  const std::string have = s && *s < lights.size() ? lights[*s].name : "none";
  if (have != arg) throw ScriptFailure(fmt::format("expected light `{}` to be selected, but `{}` is", arg, have));
  fmt::print("script: light `{}` is selected\n", have);
}

void saveLighting(EditorApp& app, ScriptState&, const std::string&) {
  const std::string saved = app.saveLighting();
  if (saved.empty()) throw ScriptFailure("the lighting was not saved");
  fmt::print("script: {}\n", saved);
}

constexpr ScriptCommand kCommands[] = {
    {"drag-ui", dragUi},
    {"expect-lights", expectLights},
    {"expect-light", expectLight},
    {"expect-lights-apart", expectLightsApart},
    {"expect-gizmo-followed", expectGizmoFollowed},
    {"expect-selected-light", expectSelectedLight},
    {"save-lighting", saveLighting},
};

}  // namespace

std::span<const ScriptCommand> lightScriptCommands() { return kCommands; }

}  // namespace tl::editor
