// The Buffers panel: the graph's resources and the buffer viewer.
#pragma once

namespace tl::editor {

class EditorApp;
void buffersPanel(EditorApp& app, bool& open);

}  // namespace tl::editor
