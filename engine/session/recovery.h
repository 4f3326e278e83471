// The editor's recovery file: what an artist had not saved yet (the lighting, the render
// settings, the albedo overrides), written every little while, so a crash or a killed editor
// loses at most the work since the last write. It lives in the editor's configuration folder,
// one per scene, and goes when the work is saved or discarded; one still there when its scene
// opens is the work of an editor that did not close (docs/user-guide.md, "Unsaved work").
//
// Two files: NAME.recovery.json (the scene, when, the settings and the overrides) and the
// lighting as a lighting file beside it (NAME.recovery.lighting.json, session/lighting_file.h),
// read back with the same checks as any lighting file. The lighting file is written first: a
// recovery file never names a lighting file that is not there.
#pragma once

#include "albedo/albedo_key.h"
#include "session/session.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tl::session {

struct RecoveredOverride {
  albedo::AlbedoKey key = 0;
  std::optional<glm::vec3> rgb;  // empty: the override was cleared
  std::string label;
};

struct RecoveredWork {
  std::filesystem::path scene;              // absolute
  std::string savedAt;                      // UTC, when written
  std::optional<Lighting> lighting;         // when it was not as saved
  std::optional<nlohmann::json> settings;   // the panel settings (settingsJson), when not as saved
  std::vector<RecoveredOverride> overrides;  // every combination whose override was not as saved
  bool empty() const { return !lighting && !settings && overrides.empty(); }
};

// `folder`/<scene stem>-<hash of its absolute path>.recovery.json: two scene.gltf files differ.
std::filesystem::path recoveryFile(const std::filesystem::path& folder, const std::filesystem::path& scene);

// Writes `work` (the lighting file first, then the recovery file, each atomically). Throws
// SessionError naming the file.
void writeRecovery(const std::filesystem::path& file, const RecoveredWork& work);
// Reads it back. Throws SessionError naming the file and what is wrong.
RecoveredWork readRecovery(const std::filesystem::path& file);
// Removes both files (nothing when they are not there).
void removeRecovery(const std::filesystem::path& file);

}  // namespace tl::session
