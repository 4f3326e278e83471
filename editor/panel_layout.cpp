#include "panel_layout.h"

#include <algorithm>

namespace tl::editor {

PanelLayout panelLayout(ImVec2 display, const std::array<bool, size_t(ToolPanel::Count)>& open, bool shaderErrors) {
  PanelLayout l;
  const float top = PanelLayout::kMenuBar, bottom = display.y - PanelLayout::kStatusBar;
  const size_t tools = size_t(std::count(open.begin(), open.end(), true));
  // The tool column narrows on a small window rather than leave the viewport nothing.
  const float free = display.x - PanelLayout::kLeftColumn - PanelLayout::kRightColumn;
  const float toolWidth = tools ? std::min(PanelLayout::kToolColumn, 0.6f * free) : 0.0f;
  const float left = PanelLayout::kLeftColumn + toolWidth;
  const float width = std::max(display.x - PanelLayout::kRightColumn - left, 1.0f);
  const float errors = shaderErrors ? std::min(PanelLayout::kShaderErrors, 0.4f * (bottom - top)) : 0.0f;
  l.viewportPos = ImVec2(left, top);
  l.viewportSize = ImVec2(width, std::max(bottom - top - errors, 1.0f));
  l.shaderErrorsPos = ImVec2(left, bottom - errors);
  l.shaderErrorsSize = ImVec2(width, errors);
  // Open tool panels share the column's height, in the order of ToolPanel.
  const float each = tools ? (bottom - top) / float(tools) : 0.0f;
  size_t slot = 0;
  for (size_t i = 0; i < open.size(); ++i) {
    if (!open[i]) continue;
    l.toolPos[i] = ImVec2(PanelLayout::kLeftColumn, top + each * float(slot++));
    l.toolSize[i] = ImVec2(toolWidth, each);
  }
  return l;
}

void placeToolPanel(const PanelLayout& layout, ToolPanel panel) {
  ImGui::SetNextWindowPos(layout.toolPos[size_t(panel)], ImGuiCond_Always);
  ImGui::SetNextWindowSize(layout.toolSize[size_t(panel)], ImGuiCond_Always);
}

}  // namespace tl::editor
