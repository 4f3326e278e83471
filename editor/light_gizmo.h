// The viewport's lights: an icon for each light where it stands, and for the selected one a
// gizmo (Debian has no gizmo library, so it is written here): three arrows that move it along
// the world's X, Y and Z, and for a light that has a direction a knob at the end of its beam
// that aims it (the light turns to look at where the knob is dragged, on a sphere around it).
// Pure geometry on the editor camera's projection: the panels draw it, the camera input drags it.
#pragma once

#include "scene/scene.h"
#include "session/session.h"

#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <vector>

struct ImDrawList;

namespace tl::editor {

struct WorldRay {
  glm::dvec3 origin, direction;  // direction unit length
};

// The editor camera's view mapped onto the viewport panel (window pixels).
struct ViewportProjection {
  session::View view;
  glm::vec2 min{0.0f}, size{0.0f};
  // Where `world` shows in the window; empty behind the camera.
  std::optional<glm::vec2> toWindow(const glm::dvec3& world) const;
  // The ray from the camera through a window pixel.
  WorldRay rayThrough(glm::vec2 window) const;
  // Metres one pixel spans at `world` (its distance along the view; the same everywhere orthographic).
  double metresPerPixel(const glm::dvec3& world) const;
  bool valid() const { return size.x > 1.0f && size.y > 1.0f; }
};

enum class GizmoHandle { None, MoveX, MoveY, MoveZ, Aim };
const char* gizmoHandleName(GizmoHandle h);  // "gizmo.move.x", ..., "gizmo.aim" (scripts click these)

// A light's place on screen and its handles.
struct GizmoGeometry {
  glm::vec2 centre{0.0f};
  glm::vec2 axisEnd[3]{};            // the X, Y and Z arrows' tips
  std::optional<glm::vec2> aimKnob;  // lights with a direction
  double armMetres = 1.0;            // the arrows' length in the world
};
std::optional<GizmoGeometry> gizmoGeometry(const ViewportProjection& p, const scene::Light& light);
// The handle under the mouse, if any.
GizmoHandle gizmoHandleAt(const GizmoGeometry& g, glm::vec2 mouse);

// A drag under way: where it started, and the light as it was then.
struct GizmoDrag {
  GizmoHandle handle = GizmoHandle::None;
  size_t light = 0;
  scene::Light start;
  WorldRay startRay{};
  glm::vec2 startMouse{0.0f};
  double armMetres = 1.0;
};
// The light after dragging the handle from the drag's start to `mouse`: an arrow moves it along
// its axis as far as the mouse ray passes along it; the knob aims it at the mouse ray's point on
// the sphere of the arm's radius (the nearest point of the ray to the light when it misses).
scene::Light draggedLight(const GizmoDrag& drag, const ViewportProjection& p, glm::vec2 mouse);
// For an arrow: the point of its axis the press grabbed (the nearest to the press's ray).
std::optional<glm::dvec3> grabbedPoint(const GizmoDrag& drag);
// The world axis an arrow moves along.
glm::dvec3 gizmoAxis(GizmoHandle h);

// The index of the light whose icon is under the mouse (the nearest within a few pixels).
std::optional<size_t> lightIconAt(const ViewportProjection& p, const std::vector<scene::Light>& lights, glm::vec2 mouse);
// Where the icon of a light is drawn: its position (a directional light has none: its icon
// stands where the artist last put it, or at the origin).
glm::dvec3 iconPosition(const scene::Light& light);

// Draws every light's icon and the selected light's gizmo into the viewport's draw list and
// records each icon ("light.icon.N") and handle for scripts (ui_helpers.h trackRect).
void drawLightOverlay(ImDrawList* draw, const ViewportProjection& p, const std::vector<scene::Light>& lights,
                      std::optional<size_t> selected, GizmoHandle active);

// A light's intensity unit as glTF and the lighting file use it: lux, cd or nits.
const char* lightIntensityUnit(scene::LightType t);

}  // namespace tl::editor
