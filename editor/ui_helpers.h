// Small Dear ImGui helpers the editor's panels share.
#pragma once

#include <imgui.h>

#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <vector>

namespace tl::editor {

// A tooltip for the last item, shown also when the item is disabled (to say why).
void tooltip(const char* text);

// Remembers where the last item was drawn this frame under `name` ("compare.difference"),
// so a script can click it as a person would (through the window's input, where Dear ImGui
// decides which window is under the cursor).
void trackItem(const std::string& name);
struct ItemRect {
  glm::vec2 min, max;
  bool visible = true;  // whole inside its window's visible area (not scrolled out, not collapsed)
  bool covered = false;  // another window lies over its centre
};
std::optional<ItemRect> trackedItem(const std::string& name);
// The same for something drawn without a widget (the viewport's light icons and gizmo handles),
// from inside the window that draws it.
void trackRect(const std::string& name, glm::vec2 min, glm::vec2 max);
// Asks the window that draws `name` next to scroll it to its middle, as a person scrolls to a
// control before clicking it.
void scrollToItem(const std::string& name);
// Asks for the window that draws `name` to come to the front, as a person clicks a window
// that another covers before clicking a control in it.
void raiseItemWindow(const std::string& name);
// Called once a frame before the panels draw: items not drawn again are forgotten.
void beginTrackedFrame();

// Labels that do not fit their window: a label is measured where tooltip() or trackItem()
// follows it, and every window's content (text, tables, widgets) is measured against what the
// window shows (checkWindowsFit); expect-labels-fit in scripts reads the list of the last frame.
const std::vector<std::string>& clippedLabels();
// Called once a frame after the panels drew: every window shown whose content reaches past its
// right edge without a horizontal scrollbar to reach it (text cut off) goes on that list (text
// cut inside a table cell is not seen: tables here wrap or scroll).
void checkWindowsFit();

}  // namespace tl::editor
