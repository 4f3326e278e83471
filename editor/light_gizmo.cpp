#include "light_gizmo.h"

#include "ui_helpers.h"

#include "session/view_math.h"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>

namespace tl::editor {
namespace {

constexpr float kArmPixels = 72.0f;    // an arrow's length on screen
constexpr float kGrabPixels = 7.0f;    // how near the mouse has to be to grab a handle
constexpr float kIconRadius = 9.0f;
constexpr double kAimArm = 1.35;       // the knob's distance in arms

const glm::dvec3 kAxes[3] = {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
const ImU32 kAxisColours[3] = {IM_COL32(230, 70, 70, 255), IM_COL32(90, 210, 90, 255), IM_COL32(80, 130, 255, 255)};

bool aimed(scene::LightType t) { return t != scene::LightType::Point; }

float distanceToSegment(glm::vec2 p, glm::vec2 a, glm::vec2 b) {
  const glm::vec2 ab = b - a;
  const float t = glm::dot(ab, ab) > 0.0f ? std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0f, 1.0f) : 0.0f;
  return glm::length(p - (a + t * ab));
}

// The parameter along line (o, d) of its point nearest to the ray; empty when they are parallel.
std::optional<double> nearestAlongLine(const glm::dvec3& o, const glm::dvec3& d, const WorldRay& ray) {
  const glm::dvec3 w = o - ray.origin;
  const double b = glm::dot(d, ray.direction), dd = glm::dot(d, d);
  const double denom = dd - b * b;  // ray direction has unit length
  if (std::abs(denom) < 1e-9 * dd) return std::nullopt;
  return (b * glm::dot(ray.direction, w) - glm::dot(d, w)) / denom;
}

ImU32 colourOf(const scene::Light& l, bool dim) {
  const float m = std::max({l.color.r, l.color.g, l.color.b, 1e-6f});
  const glm::vec3 c = l.color / m;
  const float a = dim ? 0.45f : 1.0f;
  return ImGui::GetColorU32(ImVec4(0.35f + 0.65f * c.r, 0.35f + 0.65f * c.g, 0.35f + 0.65f * c.b, a));
}

}  // namespace

std::optional<glm::vec2> ViewportProjection::toWindow(const glm::dvec3& world) const {
  if (!valid()) return std::nullopt;
  const auto m = session::cameraMatrices(view, double(size.x) / double(size.y));
  const glm::dvec4 clip = m.viewProj * glm::dvec4(world - view.position, 1.0);
  if (!(clip.w > 1e-9)) return std::nullopt;
  const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
  return min + glm::vec2(float((ndc.x * 0.5 + 0.5) * size.x), float((ndc.y * 0.5 + 0.5) * size.y));
}

WorldRay ViewportProjection::rayThrough(glm::vec2 window) const {
  const auto m = session::cameraMatrices(view, double(std::max(size.x, 1.0f)) / double(std::max(size.y, 1.0f)));
  const glm::dmat4 inverse = glm::inverse(m.viewProj);
  const glm::dvec2 ndc = glm::dvec2((window - min) / glm::max(size, glm::vec2(1.0f))) * 2.0 - 1.0;
  // Two depths of reversed Z: the near plane (1) and one beyond it (0.5; finite for both projections).
  const glm::dvec4 a = inverse * glm::dvec4(ndc, 1.0, 1.0), b = inverse * glm::dvec4(ndc, 0.5, 1.0);
  const glm::dvec3 pa = glm::dvec3(a) / a.w, pb = glm::dvec3(b) / b.w;
  return {view.position + pa, glm::normalize(pb - pa)};
}

double ViewportProjection::metresPerPixel(const glm::dvec3& world) const {
  if (!valid()) return 1e-3;
  if (view.orthographic) return 2.0 * double(view.orthoHalfHeight) / double(size.y);
  const double depth = std::max(glm::dot(world - view.position, glm::normalize(view.forward)), double(view.znear));
  return 2.0 * depth * std::tan(0.5 * double(view.yfovRadians)) / double(size.y);
}

const char* gizmoHandleName(GizmoHandle h) {
  switch (h) {
    case GizmoHandle::MoveX: return "gizmo.move.x";
    case GizmoHandle::MoveY: return "gizmo.move.y";
    case GizmoHandle::MoveZ: return "gizmo.move.z";
    case GizmoHandle::Aim: return "gizmo.aim";
    case GizmoHandle::None: break;
  }
  return "gizmo.none";
}

glm::dvec3 iconPosition(const scene::Light& light) { return light.position; }

std::optional<GizmoGeometry> gizmoGeometry(const ViewportProjection& p, const scene::Light& light) {
  const glm::dvec3 at = iconPosition(light);
  const auto centre = p.toWindow(at);
  if (!centre) return std::nullopt;
  GizmoGeometry g;
  g.centre = *centre;
  g.armMetres = kArmPixels * p.metresPerPixel(at);
  for (int a = 0; a < 3; ++a) {
    const auto end = p.toWindow(at + kAxes[a] * g.armMetres);
    g.axisEnd[a] = end ? *end : g.centre;
  }
  if (aimed(light.type)) g.aimKnob = p.toWindow(at + glm::normalize(light.direction) * (kAimArm * g.armMetres));
  return g;
}

GizmoHandle gizmoHandleAt(const GizmoGeometry& g, glm::vec2 mouse) {
  // The knob first: it sits on the beam, which may cross an arrow.
  if (g.aimKnob && glm::length(mouse - *g.aimKnob) <= kGrabPixels + 2.0f) return GizmoHandle::Aim;
  GizmoHandle best = GizmoHandle::None;
  float nearest = kGrabPixels;
  for (int a = 0; a < 3; ++a) {
    if (glm::length(g.axisEnd[a] - g.centre) < 4.0f) continue;  // pointing at the camera: not grabbable
    // Not the first pixels at the centre, where the three arrows meet (the icon is there).
    const glm::vec2 from = g.centre + 0.2f * (g.axisEnd[a] - g.centre);
    const float d = distanceToSegment(mouse, from, g.axisEnd[a]);
    if (d < nearest) nearest = d, best = GizmoHandle(int(GizmoHandle::MoveX) + a);
  }
  return best;
}

scene::Light draggedLight(const GizmoDrag& drag, const ViewportProjection& p, glm::vec2 mouse) {
  scene::Light l = drag.start;
  const WorldRay ray = p.rayThrough(mouse);
  const glm::dvec3 at = iconPosition(drag.start);
  if (drag.handle == GizmoHandle::Aim) {
    // Where the mouse ray meets the sphere of the knob's radius (its near side), else the ray's
    // point nearest to the light pushed onto the sphere.
    const double r = kAimArm * drag.armMetres;
    const glm::dvec3 oc = ray.origin - at;
    const double b = glm::dot(oc, ray.direction), c = glm::dot(oc, oc) - r * r, disc = b * b - c;
    glm::dvec3 onSphere;
    if (disc >= 0.0 && -b - std::sqrt(disc) > 0.0) onSphere = ray.origin + ray.direction * (-b - std::sqrt(disc));
    else onSphere = ray.origin + ray.direction * std::max(-b, 0.0);
    const glm::dvec3 d = onSphere - at;
    if (glm::length(d) > 1e-9) l.direction = glm::normalize(d);
    return l;
  }
  if (drag.handle == GizmoHandle::None) return l;
  const glm::dvec3 axis = gizmoAxis(drag.handle);
  const auto t0 = nearestAlongLine(at, axis, drag.startRay), t1 = nearestAlongLine(at, axis, ray);
  if (!t0 || !t1) return l;
  // Never further than the scene's limits in one drag: a ray almost along the axis runs far away.
  const double limit = 1e4 * drag.armMetres;
  l.position = drag.start.position + axis * std::clamp(*t1 - *t0, -limit, limit);
  return l;
}

glm::dvec3 gizmoAxis(GizmoHandle h) {
  const int a = int(h) - int(GizmoHandle::MoveX);
  return a >= 0 && a < 3 ? kAxes[a] : glm::dvec3(0.0);
}

std::optional<glm::dvec3> grabbedPoint(const GizmoDrag& drag) {
  const glm::dvec3 axis = gizmoAxis(drag.handle), at = iconPosition(drag.start);
  if (axis == glm::dvec3(0.0)) return std::nullopt;
  const auto t = nearestAlongLine(at, axis, drag.startRay);
  if (!t) return std::nullopt;
  return at + axis * *t;
}

std::optional<size_t> lightIconAt(const ViewportProjection& p, const std::vector<scene::Light>& lights, glm::vec2 mouse) {
  std::optional<size_t> best;
  float nearest = kIconRadius + 2.0f;
  for (size_t i = 0; i < lights.size(); ++i) {
    const auto at = p.toWindow(iconPosition(lights[i]));
    if (!at) continue;
    const float d = glm::length(*at - mouse);
    if (d < nearest) nearest = d, best = i;
  }
  return best;
}

const char* lightIntensityUnit(scene::LightType t) {
  if (t == scene::LightType::Directional) return "lux";
  return scene::isAreaLight(t) ? "nits" : "cd";
}

void drawLightOverlay(ImDrawList* draw, const ViewportProjection& p, const std::vector<scene::Light>& lights,
                      std::optional<size_t> selected, GizmoHandle active) {
  if (!p.valid()) return;
  const auto vec = [](glm::vec2 v) { return ImVec2(v.x, v.y); };
  draw->PushClipRect(vec(p.min), vec(p.min + p.size), true);
  for (size_t i = 0; i < lights.size(); ++i) {
    const scene::Light& l = lights[i];
    const auto at = p.toWindow(iconPosition(l));
    if (!at) continue;
    const ImU32 colour = colourOf(l, l.hidden);
    const bool isSelected = selected && *selected == i;
    // A beam for lights with a direction: the way they shine.
    if (aimed(l.type) && !isSelected) {
      const double arm = kArmPixels * 0.6 * p.metresPerPixel(iconPosition(l));
      if (const auto tip = p.toWindow(iconPosition(l) + glm::normalize(l.direction) * arm))
        draw->AddLine(vec(*at), vec(*tip), colour, 1.5f);
    }
    if (l.hidden) draw->AddCircle(vec(*at), kIconRadius, colour, 16, 1.5f);
    else draw->AddCircleFilled(vec(*at), kIconRadius, IM_COL32(20, 20, 24, 200), 16), draw->AddCircle(vec(*at), kIconRadius, colour, 16, 2.0f);
    const char letter[2] = {char(std::toupper(scene::lightTypeName(l.type)[0])), 0};
    const ImVec2 text = ImGui::CalcTextSize(letter);
    draw->AddText(ImVec2(at->x - 0.5f * text.x, at->y - 0.5f * text.y), colour, letter);
    if (isSelected) draw->AddCircle(vec(*at), kIconRadius + 3.0f, IM_COL32(255, 220, 80, 255), 20, 2.0f);
    trackRect(fmt::format("light.icon.{}", i), *at - glm::vec2(kIconRadius), *at + glm::vec2(kIconRadius));
  }
  if (selected && *selected < lights.size()) {
    if (const auto g = gizmoGeometry(p, lights[*selected])) {
      for (int a = 0; a < 3; ++a) {
        if (glm::length(g->axisEnd[a] - g->centre) < 4.0f) continue;
        const bool hot = active == GizmoHandle(int(GizmoHandle::MoveX) + a);
        const glm::vec2 dir = glm::normalize(g->axisEnd[a] - g->centre), side(-dir.y, dir.x);
        draw->AddLine(vec(g->centre + dir * kIconRadius), vec(g->axisEnd[a]), kAxisColours[a], hot ? 4.0f : 2.5f);
        draw->AddTriangleFilled(vec(g->axisEnd[a] + dir * 10.0f), vec(g->axisEnd[a] + side * 5.0f),
                                vec(g->axisEnd[a] - side * 5.0f), kAxisColours[a]);
        // Grabbed along its outer part (gizmoHandleAt): that part is what a script drags.
        const glm::vec2 grab = g->centre + 0.7f * (g->axisEnd[a] - g->centre);
        trackRect(gizmoHandleName(GizmoHandle(int(GizmoHandle::MoveX) + a)), grab - glm::vec2(3.0f), grab + glm::vec2(3.0f));
      }
      if (g->aimKnob) {
        const bool hot = active == GizmoHandle::Aim;
        draw->AddLine(vec(g->centre), vec(*g->aimKnob), IM_COL32(255, 220, 80, 220), 1.5f);
        draw->AddCircleFilled(vec(*g->aimKnob), hot ? 8.0f : 6.0f, IM_COL32(255, 220, 80, 255), 16);
        trackRect(gizmoHandleName(GizmoHandle::Aim), *g->aimKnob - glm::vec2(3.0f), *g->aimKnob + glm::vec2(3.0f));
      }
    }
  }
  draw->PopClipRect();
}

}  // namespace tl::editor
