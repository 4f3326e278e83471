// The outliner's Lights tab (every light but the sun: add, duplicate, delete, hide, solo), the
// inspector's view of the selected light (its properties in glTF's units) and the Lighting
// panel's environment map section.
// Every edit goes through Session::setLighting, so the edit history makes it undoable.
#pragma once

namespace tl::editor {

class EditorApp;

void lightsOutlinerTab(EditorApp& app);
// Returns false when no light is selected (the inspector shows the instance then).
bool lightInspector(EditorApp& app);
void environmentSection(EditorApp& app);

}  // namespace tl::editor
