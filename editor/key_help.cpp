#include "key_help.h"

namespace tl::editor {

std::span<const KeyHelp> keyHelp() {
  static const KeyHelp rows[] = {
      {"Camera", "Left drag", "orbit around the pivot"},
      {"Camera", "Middle drag", "pan"},
      {"Camera", "Wheel", "dolly towards the pivot"},
      {"Camera", "Right drag", "fly: look around"},
      {"Camera", "Right + W A S D", "fly forwards / left / back / right"},
      {"Camera", "Right + Q E", "fly down / up"},
      {"Camera", "Left Shift", "move 4x faster while flying"},
      {"Camera", "F", "focus on the selection (or the whole scene)"},
      {"Camera", "1 .. 9", "recall camera bookmark"},
      {"Camera", "Ctrl + 1 .. 9", "save camera bookmark (compare --cameras bookmarks measures them)"},
      {"Selection", "Left click", "select the instance under the cursor"},
      {"Albedo", "Ctrl + Z", "undo the last albedo override edit"},
      {"Albedo", "Ctrl + Shift + Z, Ctrl + Y", "redo"},
      {"Albedo", "Ctrl + S", "save the albedo overrides into the database"},
      {"Viewer", "Ctrl + Wheel", "zoom the viewed buffer around the cursor (texel borders from 8x)"},
      {"Viewer", "Hover", "probe the texel under the cursor (Buffers panel: raw and decoded values)"},
      {"Compare", "Left drag on the wipe line", "move the split between the two paths"},
      {"Panels", "F1", "this window"},
      {"Panels", "F2", "Buffers: every buffer of the frame, with the viewer"},
      {"Panels", "F3", "Compare: two paths side by side, errors against the reference"},
      {"Files", "Ctrl + O", "open a scene (or drop one onto the window)"},
      {"Files", "F12", "RenderDoc capture of the next frame (when running under RenderDoc)"},
  };
  return rows;
}

}  // namespace tl::editor
