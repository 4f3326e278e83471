// Saving lights back into an artist's glTF as KHR_lights_punctual. The lights and the nodes that
// place them are written into the file's own JSON (a .gltf, or a .glb's JSON chunk with every
// chunk after it kept byte for byte), so nothing else of the file changes: meshes, materials,
// textures, animations, other extensions and the order of everything stay as exported.
#pragma once

#include "scene/scene.h"

#include <filesystem>
#include <vector>

namespace tl::session {

// Replaces the file's KHR_lights_punctual lights with `lights` (directional, point and spot, in
// glTF's units: lux, candela). A light whose `node` names a node that holds a light and nothing
// else (no mesh, camera, children or skin, and no animation moves it) is written there, moved to
// the light's place through its parents' transforms; any other light gets a new node at the root
// of the file's scene. The first directional light of `lights` loads back as the sun: it is the
// first light the importer meets (a new first root when its node would be met after another
// directional light). Nodes whose light is no longer saved keep their place and lose the light.
// Returns, per light, the node it now lives on. Throws SessionError naming the file (which is
// left as it was) when it cannot be read, parsed or written, or when a light is an area light.
std::vector<uint32_t> writeGltfLights(const std::filesystem::path& file, const std::vector<scene::Light>& lights);

}  // namespace tl::session
