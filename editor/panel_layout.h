// Where the editor's panels sit, for any window size: the Outliner and the Inspector in the left
// column, the Lighting, Timing and Albedo panels in the right one, the viewport between them.
// The tool panels (Scene, Buffers, Compare, Help) open in a column of their own beside the left
// one, stacked, and the viewport gives them the room; the Shader errors window takes a strip
// under the viewport. No panel opens over the image: the viewport is what an artist looks at.
// (The file browser, a dialog that goes once a scene is chosen, still opens in the middle.)
#pragma once

#include <imgui.h>

#include <array>

namespace tl::editor {

enum class ToolPanel { Scene, Buffers, Compare, Help, Count };

struct PanelLayout {
  static constexpr float kMenuBar = 20.0f, kStatusBar = 24.0f;
  static constexpr float kLeftColumn = 300.0f, kRightColumn = 340.0f, kToolColumn = 480.0f, kShaderErrors = 170.0f;
  ImVec2 viewportPos, viewportSize;
  ImVec2 shaderErrorsPos, shaderErrorsSize;
  std::array<ImVec2, size_t(ToolPanel::Count)> toolPos{}, toolSize{};
};

// The layout for a window of `display` size with the tool panels `open` (by ToolPanel) and the
// Shader errors window shown or not.
PanelLayout panelLayout(ImVec2 display, const std::array<bool, size_t(ToolPanel::Count)>& open, bool shaderErrors);

// Places the next window (the tool panel's Begin follows) where the layout has it.
void placeToolPanel(const PanelLayout& layout, ToolPanel panel);

}  // namespace tl::editor
