// The albedo database in the editor: the inspector's albedo section for the selected
// instance and the Albedo panel (entries, filters, bake). Edits go through the session's
// AlbedoLibrary, so undo/redo and save behave as in the tests.
#pragma once

#include <cstdint>

namespace tl::editor {

class EditorApp;

void albedoInspectorSection(EditorApp& app, uint32_t instance);
void albedoPanel(EditorApp& app);

}  // namespace tl::editor
