// The Compare panel (F3): two lighting paths side by side in the viewport, split by a wipe
// the artist drags, or as their difference, with each side's live error against the
// reference (which accumulates while the camera and light stay still).
#pragma once

namespace tl::editor {

class EditorApp;

void comparePanel(EditorApp& app);
// Labels over the viewport: which path is on which side, or the difference's legend.
void compareViewportOverlay(EditorApp& app);

}  // namespace tl::editor
