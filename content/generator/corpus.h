// The randomized interior corpus: interiors drawn at random from a seed, so that no constant
// and no threshold can be tuned to them. Each interior is drawn from its own stream (the seed
// and its index), so interior i is the same whatever the count. What is drawn, per interior:
//   scale       the main room's longest side, log-uniform from 0.5 m to 500 m;
//   shape       a box, a hall, a corridor, an L of two rooms, or a suite of rooms joined by doors;
//   openings    none, a door, windows, slits across the roof or a skylight;
//   light       the sun and the sky through the openings, or an HDRI (an environment map
//               with a sun disc, set up in the scene's lighting sidecar), emissive panels and
//               meshes, KHR point and spot lamps (every closed interior has lamps or emitters);
//   albedo      white 0.9, greys, or saturated colours;
//   walls       two triangles a wall piece (no thickness), or boxes with thickness whose faces
//               are tessellated (10k+ triangles);
//   a sealed room beside the lit one (its own camera; its true image is black), when the walls
//   have thickness.
// Units are metres; every length is drawn relative to the room, so the same draw at another
// scale is the same picture. The glTF's extras hold what was drawn
// (extras.twinlight.corpus), for the summary tables.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace tl::content {

struct CorpusScene {
  std::string name;        // file stem: "interior_007"
  std::string shape;       // box, hall, corridor, l_shape, suite
  std::string openings;    // none, door, windows, slits, skylight
  std::string lights;      // "+"-joined: sun, sky, hdri, panels, emitter, lamps, spots
  std::string albedo;      // white, grey, saturated
  std::string walls;       // quads, thick
  float size = 0.0f;       // the main room's longest side, metres
  uint32_t triangles = 0;
  bool sealedRoom = false;  // camera 1 looks at the inside of a sealed room
};

// Writes interiors `first` .. `first + count - 1` of corpus `seed` into `dir` (.gltf + .bin
// each) and returns what was drawn. Throws std::runtime_error on a failed write.
std::vector<CorpusScene> writeCorpus(const std::filesystem::path& dir, uint64_t seed, uint32_t first, uint32_t count);

}  // namespace tl::content
