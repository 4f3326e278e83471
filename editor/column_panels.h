// Where the column panels sit for the window's size: the Outliner over the Inspector in the left
// column, the Lighting, Timing and Albedo panels stacked in the right one (panel_layout.h keeps
// the viewport and the tool panels between them). Their heights are shares of the window's, so a
// smaller window keeps every panel inside it; when the window's size changes they are laid out
// again (an artist's own moves and sizes last until then).
#pragma once

namespace tl::editor {

enum class ColumnPanel { Outliner, Inspector, Lighting, Timing, Albedo };

// Once a frame, before the panels: notes whether the window's size changed since the last frame.
void beginColumnLayout();

// Places the next window (the column panel's Begin follows) where the layout has it.
void placeColumnPanel(ColumnPanel panel);

}  // namespace tl::editor
