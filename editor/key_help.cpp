#include "key_help.h"

namespace tl::editor {

std::span<const KeyHelp> keyHelp() {
  // Rows of a section stay together: the F1 window draws one table per section.
  static const KeyHelp rows[] = {
      {"Camera (over the viewport)", "Left drag", "orbit around the pivot"},
      {"Camera (over the viewport)", "Left click", "select the instance under the cursor"},
      {"Camera (over the viewport)", "Middle drag", "pan"},
      {"Camera (over the viewport)", "Wheel", "dolly towards the pivot"},
      {"Camera (over the viewport)", "Right drag", "fly: look around"},
      {"Camera (over the viewport)", "Right + W A S D", "fly forwards / left / back / right"},
      {"Camera (over the viewport)", "Right + Q E", "fly down / up"},
      {"Camera (over the viewport)", "Shift", "move 4x faster while flying"},
      {"Camera (over the viewport)", "F", "focus on the selection (or the whole scene)"},
      {"Camera (over the viewport)", "1 .. 9", "recall camera bookmark"},
      {"Camera (over the viewport)", "Ctrl + 1 .. 9", "save camera bookmark (compare --cameras bookmarks)"},
      {"Edits", "Ctrl + Z", "undo the latest edit: a render setting, the lighting or an albedo override"},
      {"Edits", "Ctrl + Y, Ctrl + Shift + Z", "redo the edit undone last"},
      {"Edits", "Ctrl + S", "File > Save: the lights (into the glTF and its sidecar), the albedo overrides, the render settings"},
      {"Windows", "F1", "this window"},
      {"Windows", "F2", "Buffers: every resource of the frame, the viewer"},
      {"Windows", "F3", "Compare: two paths side by side, their error"},
      {"Windows", "F12", "RenderDoc capture of the next engine frame (under RenderDoc)"},
      {"Windows", "Ctrl + O", "open a scene or a capture"},
      {"Buffer viewer (a resource in the viewport)", "Ctrl + Wheel", "zoom around the cursor (texel grid from 8x)"},
      {"Buffer viewer (a resource in the viewport)", "Hover", "probe: stored values and what they mean"},
      {"Buffer viewer (a resource in the viewport)", "Meaning / Raw", "what the buffer means, or its stored channels"},
      {"Buffer viewer (a resource in the viewport)", "Keep as B / show B", "A/B against a kept copy"},
      {"Compare view", "Left drag on the wipe line", "move the split between the two paths"},
      {"Files", "File > Save image", "the frame as PNG (display) or EXR (linear) into renders/"},
      {"Files", "File > Reload scene", "load the file again (automatic when it changes on disk)"},
  };
  return rows;
}

}  // namespace tl::editor
