#include "session/edit_history.h"

#include <fmt/format.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace tl::session {

namespace {

// Equal but for float rounding: a few units in the last place of a float, relative to the
// larger length (a glTF node holds floats; the light's own vectors are doubles).
constexpr double kFloatRounding = 4.0 * double(std::numeric_limits<float>::epsilon());
bool nearlySame(const glm::dvec3& a, const glm::dvec3& b) {
  return glm::length(a - b) <= kFloatRounding * std::max({glm::length(a), glm::length(b), 1e-30});
}
bool nearlySame(const glm::vec3& a, const glm::vec3& b) { return nearlySame(glm::dvec3(a), glm::dvec3(b)); }
bool nearlySame(float a, float b) { return std::abs(double(a) - double(b)) <= kFloatRounding * std::max(std::abs(double(a)), std::abs(double(b))); }

// One map whether it is the same object or the same file read again (a reload reads it anew while
// the artist's kept lighting holds the copy read before): compared by what it holds.
bool sameEnvironmentMap(const std::shared_ptr<const scene::EnvironmentMap>& a,
                        const std::shared_ptr<const scene::EnvironmentMap>& b) {
  if (a == b) return true;
  if (!a || !b) return false;
  return a->path == b->path && a->width == b->width && a->height == b->height && a->contentHash == b->contentHash;
}

}  // namespace

bool sameLight(const scene::Light& a, const scene::Light& b) {
  using scene::LightType;
  if (a.name != b.name || a.type != b.type || !nearlySame(a.color, b.color) || !nearlySame(a.intensity, b.intensity) ||
      a.range.has_value() != b.range.has_value() || (a.range && !nearlySame(*a.range, *b.range)) ||
      a.hidden != b.hidden || !nearlySame(a.position, b.position))
    return false;
  switch (a.type) {
    case LightType::Point: return true;
    case LightType::Directional: return nearlySame(a.direction, b.direction);
    case LightType::Spot:
      return nearlySame(a.direction, b.direction) && a.innerConeAngle == b.innerConeAngle && a.outerConeAngle == b.outerConeAngle;
    case LightType::Rect:
      return nearlySame(a.direction, b.direction) && nearlySame(a.widthAxis, b.widthAxis) && a.width == b.width &&
             a.height == b.height && a.twoSided == b.twoSided;
    case LightType::Disk: return nearlySame(a.direction, b.direction) && a.radius == b.radius && a.twoSided == b.twoSided;
    case LightType::Tube: return nearlySame(a.direction, b.direction) && a.radius == b.radius && a.length == b.length;
  }
  return false;
}

bool sameLighting(const Lighting& a, const Lighting& b) {
  return a.sunDirection == b.sunDirection && a.sunIrradiance == b.sunIrradiance && a.skyRadiance == b.skyRadiance &&
         a.exposureEv == b.exposureEv && a.sunAngularRadius == b.sunAngularRadius &&
         sameEnvironmentMap(a.environmentMap, b.environmentMap) && a.environmentRotation == b.environmentRotation &&
         a.environmentIntensity == b.environmentIntensity &&
         std::equal(a.lights.begin(), a.lights.end(), b.lights.begin(), b.lights.end(), sameLight);
}

void EditHistory::reset(const lighting::RenderSettings& settings, const Lighting& lighting) {
  steps_.clear();
  done_ = 0;
  seenSettings_ = settings;
  seenLighting_ = lighting;
  watching_ = true;
}

bool EditHistory::Step::sameKind(const Step& other) const {
  if (settings.size() != other.settings.size() || lightingBefore.has_value() != other.lightingBefore.has_value())
    return false;
  for (size_t i = 0; i < settings.size(); ++i)
    if (settings[i].setting != other.settings[i].setting) return false;
  return true;
}

bool EditHistory::observe(const lighting::RenderSettings& settings, const Lighting& lighting, bool continuing) {
  if (!watching_) {
    reset(settings, lighting);
    return false;
  }
  Step step;
  for (const lighting::SettingInfo& s : lighting::settingsSchema()) {
    if (s.flags & lighting::kSettingNoPanel) continue;  // the image size follows the viewport
    const double before = s.get(seenSettings_), after = s.get(settings);
    if (before != after) step.settings.push_back({&s, before, after});
  }
  if (!sameLighting(lighting, seenLighting_)) step.lightingBefore = seenLighting_, step.lightingAfter = lighting;
  seenSettings_ = settings;
  seenLighting_ = lighting;
  if (step.settings.empty() && !step.lightingBefore) return false;
  step.madeAt = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  steps_.resize(done_);  // a new edit drops what could be redone
  if (continuing && !steps_.empty() && steps_.back().sameKind(step)) {
    Step& last = steps_.back();
    for (size_t i = 0; i < step.settings.size(); ++i) last.settings[i].after = step.settings[i].after;
    if (step.lightingAfter) last.lightingAfter = step.lightingAfter;
    last.madeAt = step.madeAt;
  } else {
    steps_.push_back(std::move(step));
    ++done_;
  }
  return true;
}

void EditHistory::apply(const Step& step, bool forward, lighting::RenderSettings& settings, Lighting& lighting) {
  for (const Change& c : step.settings) c.setting->set(settings, forward ? c.after : c.before);
  if (step.lightingBefore) lighting = forward ? *step.lightingAfter : *step.lightingBefore;
  seenSettings_ = settings;  // not a new edit
  seenLighting_ = lighting;
}

bool EditHistory::undo(lighting::RenderSettings& settings, Lighting& lighting) {
  if (!canUndo()) return false;
  --done_;
  apply(steps_[done_], false, settings, lighting);
  return true;
}

bool EditHistory::redo(lighting::RenderSettings& settings, Lighting& lighting) {
  if (!canRedo()) return false;
  apply(steps_[done_], true, settings, lighting);
  ++done_;
  return true;
}

std::string EditHistory::describe(const Step& step, bool forward) {
  std::string text;
  for (const Change& c : step.settings) {
    if (!text.empty()) text += ", ";
    if (text.size() > 60) return text + "...";
    text += fmt::format("{} {} -> {}", c.setting->name, lighting::formatSetting(*c.setting, forward ? c.before : c.after),
                        lighting::formatSetting(*c.setting, forward ? c.after : c.before));
  }
  if (step.lightingBefore) text += text.empty() ? "lighting" : ", lighting";
  return text;
}

std::optional<double> EditHistory::undoTime() const {
  return canUndo() ? std::optional<double>(steps_[done_ - 1].madeAt) : std::nullopt;
}

std::optional<double> EditHistory::redoTime() const {
  return canRedo() ? std::optional<double>(steps_[done_].madeAt) : std::nullopt;
}

std::string EditHistory::undoLabel() const { return canUndo() ? describe(steps_[done_ - 1], false) : std::string(); }
std::string EditHistory::redoLabel() const { return canRedo() ? describe(steps_[done_], true) : std::string(); }

}  // namespace tl::session
