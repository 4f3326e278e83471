#include "ui_helpers.h"

#include <imgui_internal.h>

#include <map>
#include <vector>

namespace tl::editor {
namespace {

std::map<std::string, ItemRect> items, previousItems;
std::vector<std::string> clipped, previousClipped;
std::string scrollRequest, raiseRequest;

// Whether a window in front of `window` (a later root window, shown) contains `point`.
bool coveredAt(ImGuiWindow* window, ImVec2 point) {
  ImGuiContext& g = *GImGui;
  ImGuiWindow* root = window->RootWindow;
  bool above = false;
  for (ImGuiWindow* w : g.Windows) {
    if (w == root) {
      above = true;
      continue;
    }
    if (above && w == w->RootWindow && w->WasActive && !w->Hidden && w->Rect().Contains(point)) return true;
  }
  return false;
}

// Whether the last item (widget and label) ends inside its window's visible area; an item
// scrolled out of view or in a collapsed window does not count.
void checkLastItemFits() {
  ImGuiWindow* window = ImGui::GetCurrentWindow();
  if (!window || window->SkipItems) return;
  const ImVec2 max = ImGui::GetItemRectMax(), min = ImGui::GetItemRectMin();
  const ImRect visible = window->InnerClipRect;
  if (min.y < visible.Min.y || max.y > visible.Max.y) return;  // not on screen: nothing to read
  // A selectable's highlight reaches half an item spacing past the work area by design (its
  // text does not): that much is not a label cut off.
  if (max.x > visible.Max.x + 0.5f * ImGui::GetStyle().ItemSpacing.x + 0.5f)
    clipped.push_back(std::string(window->Name) + ": the item at y " + std::to_string(int(min.y)) + " ends at x " +
                      std::to_string(int(max.x)) + ", the window at " + std::to_string(int(visible.Max.x)));
}

}  // namespace

void tooltip(const char* text) {
  checkLastItemFits();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) ImGui::SetTooltip("%s", text);
}

void trackItem(const std::string& name) {
  checkLastItemFits();
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  ImGuiWindow* window = ImGui::GetCurrentWindow();
  const bool visible = window && !window->SkipItems && a.y >= window->InnerClipRect.Min.y &&
                       b.y <= window->InnerClipRect.Max.y;
  const bool covered = window && coveredAt(window, ImVec2(0.5f * (a.x + b.x), 0.5f * (a.y + b.y)));
  items[name] = {glm::vec2(a.x, a.y), glm::vec2(b.x, b.y), visible, covered};
  if (name == raiseRequest) {
    ImGui::FocusWindow(window->RootWindow);
    raiseRequest.clear();
  }
  if (name == scrollRequest) {
    ImGui::SetScrollHereY(0.5f);
    scrollRequest.clear();
  }
}

void trackRect(const std::string& name, glm::vec2 min, glm::vec2 max) {
  ImGuiWindow* window = ImGui::GetCurrentWindow();
  const glm::vec2 c = 0.5f * (min + max);
  items[name] = {min, max, true, window && coveredAt(window, ImVec2(c.x, c.y))};
}

void scrollToItem(const std::string& name) { scrollRequest = name; }

void raiseItemWindow(const std::string& name) { raiseRequest = name; }

std::optional<ItemRect> trackedItem(const std::string& name) {
  auto it = previousItems.find(name);
  if (it == previousItems.end()) return std::nullopt;
  return it->second;
}

void beginTrackedFrame() {
  previousItems.swap(items);
  items.clear();
  previousClipped.swap(clipped);
  clipped.clear();
}

const std::vector<std::string>& clippedLabels() { return previousClipped; }

void checkWindowsFit() {
  ImGuiContext& g = *GImGui;
  for (ImGuiWindow* w : g.Windows) {
    if (!w->Active || w->Hidden || w->SkipItems || w->ScrollbarX) continue;
    if (w->Flags & (ImGuiWindowFlags_Tooltip | ImGuiWindowFlags_ChildMenu)) continue;  // sized to their text
    // Where its content actually reaches (a table that scrolls sideways is a window of its own
    // with a scrollbar; text cut inside a table cell without one is not seen here).
    const float right = w->DC.CursorMaxPos.x;
    if (right > w->InnerClipRect.Max.x + 1.0f)
      clipped.push_back(std::string(w->Name) + ": its content reaches x " + std::to_string(int(right)) +
                        ", the window shows up to x " + std::to_string(int(w->InnerClipRect.Max.x)));
  }
}

}  // namespace tl::editor
