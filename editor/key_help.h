// Every key and mouse binding of the editor, as the F1 help window lists them. A test
// (tests/editor/check_key_help.py) reads the editor's sources: a key they handle that this
// table does not name fails it.
#pragma once

#include <span>

namespace tl::editor {

struct KeyHelp {
  const char* section;  // "Camera", "Panels", ...
  const char* keys;     // "Ctrl + Z"
  const char* action;
};

std::span<const KeyHelp> keyHelp();

}  // namespace tl::editor
