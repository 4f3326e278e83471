// Small Dear ImGui helpers the editor's panels share.
#pragma once

#include <imgui.h>

namespace tl::editor {

// A tooltip for the last item, shown also when the item is disabled (to say why).
inline void tooltip(const char* text) {
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) ImGui::SetTooltip("%s", text);
}

}  // namespace tl::editor
