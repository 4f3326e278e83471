// The lighting sidecar: SCENE.lighting.json beside a scene holds what an artist set up on top
// of it (sun, sky, environment map with its rotation and intensity, exposure, and every
// punctual and area light with its transform; area lights live only here: glTF has none), read back by `--lighting FILE` on every rendering
// subcommand. One module writes and reads it; docs/user-guide.md ("Saving lighting") shows the
// format. Every value is checked after conversion (degrees to radians, kelvin to RGB): a bad
// one is one SessionError naming the file and the key, and nothing is applied.
#pragma once

#include "session/session.h"

#include <filesystem>
#include <optional>
#include <string>

namespace tl::session {

inline constexpr const char* kLightingFormat = "twinlight.lighting";
inline constexpr int kLightingFormatVersion = 1;

// scene.gltf -> scene.lighting.json (beside it).
std::filesystem::path lightingSidecarPath(const std::filesystem::path& scene);

// `base` with what `file` sets: each top-level key present replaces that part of the lighting
// ("lights" the whole list, "environment": null the map); absent keys keep `base`'s. Relative
// environment paths are relative to the file's folder.
Lighting readLightingFile(const std::filesystem::path& file, const Lighting& base);

// The JSON text of `lighting` (every key; the environment map's path relative to `folder`
// when it lies inside it, else absolute).
std::string lightingJson(const Lighting& lighting, const std::filesystem::path& folder);

// Writes lightingJson to `file` through a temporary file renamed over it (a failed write
// leaves any earlier file intact). Throws SessionError.
void writeLightingFile(const std::filesystem::path& file, const Lighting& lighting);

// What saveSceneLighting wrote.
struct SavedLighting {
  std::filesystem::path sidecar;
  size_t gltfLights = 0;  // KHR_lights_punctual lights in the glTF, the sun included
};

// Saves what an artist set up for `scene` (the glTF the session loaded): the sun (the first
// directional light, so it loads as the sun again) and every shown punctual light into the glTF
// itself as KHR_lights_punctual, so other tools see them (session/gltf_lights_writer.h), and the
// whole lighting (area and hidden lights, sky, environment map, exposure too) into the sidecar
// beside it, which `--lighting` reads. The lights' and the sun's `node` become the nodes they
// were written to. Throws SessionError; the glTF is written first and a failure leaves both
// files as they were.
SavedLighting saveSceneLighting(const std::filesystem::path& scene, Lighting& lighting);

// The lighting a scene opens with in the editor, whichever way it is opened (at start-up, File >
// Open, a reload, the command line): the scene's own (sceneLighting, from nothing: no lighting
// carries over from the scene before), then `lightingFile` (`--lighting`, given for this scene)
// or else the sidecar beside the scene when there is one. A file with no light at all (no sun, no
// punctual light, nothing emissive) would show only the flat uniform sky: with `defaultSun` (the
// editor's choice; a headless render keeps the file's light) it gets the default sun first.
struct OpeningLighting {
  Lighting lighting;
  std::optional<std::filesystem::path> readFrom;  // the lighting file applied
  bool defaultSun = false;                        // the default sun was given
  // Why the lighting file could not be applied (the scene's own lighting is used then).
  std::string error;
};
OpeningLighting openingLighting(const scene::Scene& scene, const std::optional<std::filesystem::path>& lightingFile,
                                bool defaultSun);

}  // namespace tl::session
