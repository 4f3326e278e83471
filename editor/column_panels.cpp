#include "column_panels.h"

#include "panel_layout.h"

#include <imgui.h>

namespace tl::editor {
namespace {

// The window's size at the last frame (one editor window per process). Zero before the first
// frame, so the first one lays the panels out for the size the window opened at, whatever size a
// saved imgui.ini had them at.
ImVec2 lastDisplay{0.0f, 0.0f};
bool relayout = true;

// The column heights at the 1600 x 900 window the panels were drawn for, shared out on any other.
constexpr float kDesignHeight = 856.0f;  // 900 less the menu and status bars
constexpr float kOutliner = 420.0f, kLighting = 380.0f, kTiming = 220.0f;

}  // namespace

void beginColumnLayout() {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  relayout = display.x != lastDisplay.x || display.y != lastDisplay.y;
  lastDisplay = display;
}

void placeColumnPanel(ColumnPanel panel) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const float top = PanelLayout::kMenuBar, height = display.y - PanelLayout::kStatusBar - top;
  const float share = height / kDesignHeight;
  const float right = display.x - PanelLayout::kRightColumn;
  ImVec2 pos, size;
  switch (panel) {
    case ColumnPanel::Outliner:
      pos = ImVec2(0.0f, top), size = ImVec2(PanelLayout::kLeftColumn, kOutliner * share);
      break;
    case ColumnPanel::Inspector:
      pos = ImVec2(0.0f, top + kOutliner * share), size = ImVec2(PanelLayout::kLeftColumn, height - kOutliner * share);
      break;
    case ColumnPanel::Lighting:
      pos = ImVec2(right, top), size = ImVec2(PanelLayout::kRightColumn, kLighting * share);
      break;
    case ColumnPanel::Timing:
      pos = ImVec2(right, top + kLighting * share), size = ImVec2(PanelLayout::kRightColumn, kTiming * share);
      break;
    case ColumnPanel::Albedo:
      pos = ImVec2(right, top + (kLighting + kTiming) * share);
      size = ImVec2(PanelLayout::kRightColumn, height - (kLighting + kTiming) * share);
      break;
  }
  const ImGuiCond when = relayout ? ImGuiCond_Always : ImGuiCond_FirstUseEver;
  ImGui::SetNextWindowPos(pos, when);
  ImGui::SetNextWindowSize(size, when);
}

}  // namespace tl::editor
