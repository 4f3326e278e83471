// `compare --cameras SPEC`: the views a comparison runs from. SPEC is `bookmarks` (the
// editor's saved camera bookmarks of this scene, Ctrl+1..9), `scene` (the glTF file's
// cameras), or a comma list of glTF camera indices (`0,2`) and bookmark slots (`b1,b3`).
#pragma once

#include "session/session.h"

#include <string>
#include <vector>

namespace tl::editor {

struct NamedView {
  std::string name;  // a folder name: camera0, bookmark3
  session::View view;
};

// Throws SessionError naming what is missing (no bookmarks saved, camera out of range).
std::vector<NamedView> resolveCompareCameras(session::Session& session, const std::string& spec);

}  // namespace tl::editor
