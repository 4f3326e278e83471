// `compare --cameras SPEC`: the views a comparison runs from. SPEC is `bookmarks` (the
// editor's saved camera bookmarks of this scene, Ctrl+1..9), `scene` (the glTF file's
// cameras), or a comma list of glTF camera indices (`0,2`) and bookmark slots (`b1,b3`).
// Names come first and need no GPU (a sweep plans its whole grid before it renders, so every
// shard agrees on it); a name's view is set once its scene is loaded.
#pragma once

#include "session/session.h"

#include <filesystem>
#include <string>
#include <vector>

namespace tl::editor {

// The cameras SPEC names for `sceneFile`, in order: camera0.., bookmark1... Throws
// SessionError naming what is missing (no bookmarks saved, camera out of range). `scene` and
// glTF indices parse the file (no GPU) to know its cameras.
std::vector<std::string> compareCameraNames(const std::filesystem::path& sceneFile, const std::string& spec);

// Points the session (its scene loaded) at a camera compareCameraNames gave.
void useCompareCamera(session::Session& session, const std::string& name);

}  // namespace tl::editor
