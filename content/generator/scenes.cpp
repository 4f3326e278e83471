// The project's own scenes (units: metres, +Y up). Each one exists to make a lighting
// question measurable; content/README.md says which. Usage: tl_content_gen <content-dir>
// The scale scene is generated when measured, never committed (it is tens of megabytes):
// tl_content_gen --sprawl <dir> [instances=100000] [keys=1000]
#include "corpus.h"
#include "gltf_writer.h"
#include "hard_scenes.h"
#include "sky_map.h"

#include <OpenImageIO/imageio.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace tl::content {
namespace {

void writeChecker(const std::filesystem::path& file) {
  const int size = 64, cells = 8;
  std::vector<unsigned char> px(size * size * 3);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      bool light = ((x * cells / size) + (y * cells / size)) % 2 == 0;
      unsigned char v = light ? 220 : 45;
      for (int c = 0; c < 3; ++c) px[(y * size + x) * 3 + c] = v;
    }
  std::filesystem::create_directories(file.parent_path());
  auto out = OIIO::ImageOutput::create(file.string());
  OIIO::ImageSpec spec(size, size, 3, OIIO::TypeDesc::UINT8);
  if (!out || !out->open(file.string(), spec) || !out->write_image(OIIO::TypeDesc::UINT8, px.data()) || !out->close())
    throw std::runtime_error("cannot write " + file.string());
}

}  // namespace

// A lighting sidecar (session/lighting_file.h) beside a scene; a failed write is an error.
void writeLightingSidecar(const std::filesystem::path& file, const char* text) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out << text;
  out.close();  // a failed flush shows only after close
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

namespace {

// A box-shaped wall piece as its own node: boxes have real thickness, so light does not
// leak through the seams the way it does through single-sided quads.
void wall(SceneWriter& w, const std::string& name, int material, glm::vec3 center, glm::vec3 size) {
  w.node(name, w.mesh(name, box(size, 0.5f), material), center);
}

// A closed room of width x depth x height metres inside walls of thickness t (the floor's top
// at y = 0, centred on the origin): floor, ceiling and four walls as boxes.
void closedRoom(SceneWriter& w, int floorMat, int wallMat, float width, float depth, float h, float t) {
  wall(w, "floor", floorMat, {0.0f, -t / 2, 0.0f}, {width + 2 * t, t, depth + 2 * t});
  wall(w, "ceiling", wallMat, {0.0f, h + t / 2, 0.0f}, {width + 2 * t, t, depth + 2 * t});
  wall(w, "wall_north", wallMat, {0.0f, h / 2, -depth / 2 - t / 2}, {width, h, t});
  wall(w, "wall_south", wallMat, {0.0f, h / 2, depth / 2 + t / 2}, {width, h, t});
  wall(w, "wall_west", wallMat, {-width / 2 - t / 2, h / 2, 0.0f}, {t, h, depth});
  wall(w, "wall_east", wallMat, {width / 2 + t / 2, h / 2, 0.0f}, {t, h, depth});
}

// A 0.75 m high table: a 6 cm top of topX x topZ centred at (x, z) on four 6 cm legs, each
// legX / legZ from the centre.
void table(SceneWriter& w, int material, float x, float z, float topX, float topZ, float legX, float legZ) {
  wall(w, "table_top", material, {x, 0.75f, z}, {topX, 0.06f, topZ});
  for (int i = 0; i < 4; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "table_leg_%d", i + 1);
    wall(w, name, material, {x + ((i & 1) ? legX : -legX), 0.36f, z + ((i & 2) ? legZ : -legZ)}, {0.06f, 0.72f, 0.06f});
  }
}

void atrium(const std::filesystem::path& dir) {
  SceneWriter w("atrium");
  int floorMat = w.material({"stone_floor", {0.55f, 0.53f, 0.50f}, 0.0f, 0.85f});
  int red = w.material({"plaster_terracotta", {0.62f, 0.22f, 0.14f}, 0.0f, 0.9f});
  int ochre = w.material({"plaster_ochre", {0.76f, 0.56f, 0.22f}, 0.0f, 0.9f});
  int teal = w.material({"plaster_teal", {0.14f, 0.44f, 0.44f}, 0.0f, 0.9f});
  int white = w.material({"plaster_white", {0.80f, 0.79f, 0.76f}, 0.0f, 0.9f});
  int stone = w.material({"column_stone", {0.70f, 0.68f, 0.64f}, 0.0f, 0.7f});
  int gold = w.material({"polished_gold", {1.00f, 0.78f, 0.34f}, 1.0f, 0.25f});
  int checker = w.material({"checker_textured", {1.0f, 1.0f, 1.0f}, 0.0f, 0.6f, {}, 1.0f, "textures/checker.png"});

  wall(w, "courtyard_floor", floorMat, {0.0f, -0.1f, 0.0f}, {25.0f, 0.2f, 25.0f});
  wall(w, "wall_north_terracotta", red, {0.0f, 3.0f, -12.2f}, {24.8f, 6.0f, 0.4f});
  wall(w, "wall_west_ochre", ochre, {-12.2f, 3.0f, 0.0f}, {0.4f, 6.0f, 24.0f});
  wall(w, "wall_east_teal", teal, {12.2f, 3.0f, 0.0f}, {0.4f, 6.0f, 24.0f});

  // The interior room: 6 x 3.5 x 6 m inside a 0.25 m shell, lit only through a doorway in
  // its south wall, which faces the sun.
  const float t = 0.25f, h = 3.5f;
  wall(w, "room_wall_north", white, {5.0f, h / 2, -10.0f + t / 2}, {6.0f, h, t});
  wall(w, "room_wall_east", white, {8.0f - t / 2, h / 2, -7.0f}, {t, h, 6.0f});
  wall(w, "room_wall_west", white, {2.0f + t / 2, h / 2, -7.0f}, {t, h, 6.0f});
  wall(w, "room_wall_south_left", white, {3.1f, h / 2, -4.0f - t / 2}, {2.2f, h, t});
  wall(w, "room_wall_south_right", white, {6.9f, h / 2, -4.0f - t / 2}, {2.2f, h, t});
  wall(w, "room_door_lintel", white, {5.0f, 2.95f, -4.0f - t / 2}, {1.6f, 1.1f, t});
  wall(w, "room_ceiling", white, {5.0f, h + t / 2, -7.0f}, {6.0f, t, 6.0f});

  int columnMesh = w.mesh("column", cylinder(0.3f, 5.5f, 24), stone);
  for (int i = 0; i < 4; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "column_%02d", i + 1);
    w.node(name, columnMesh, {-9.0f + 2.5f * float(i), 0.0f, -6.0f});
  }
  w.node("metal_sphere", w.mesh("sphere", sphere(1.0f, 48, 24), gold), {-3.0f, 1.0f, 1.0f});
  w.node("checker_box", w.mesh("checker_cube", box({1.2f, 1.2f, 1.2f}, 1.0f / 1.2f), checker), {-8.0f, 0.6f, 3.0f},
         {0.0f, 25.0f, 0.0f});

  w.camera("courtyard_view", {0.0f, 3.5f, 13.0f}, {1.5f, 1.2f, -6.0f}, 55.0f);
  w.sun({0.25f, -0.55f, -0.8f}, 20.0f);
  w.sky({0.6f, 0.75f, 1.0f});
  writeChecker(dir / "textures" / "checker.png");
  w.write(dir);
}

void cornell(const std::filesystem::path& dir) {
  SceneWriter w("cornell");
  int white = w.material({"cornell_white", {0.73f, 0.73f, 0.73f}, 0.0f, 1.0f});
  int red = w.material({"cornell_red", {0.63f, 0.065f, 0.05f}, 0.0f, 1.0f});
  int green = w.material({"cornell_green", {0.14f, 0.45f, 0.091f}, 0.0f, 1.0f});
  int light = w.material({"ceiling_light", {0.78f, 0.78f, 0.78f}, 0.0f, 1.0f, {1.0f, 0.85f, 0.6f}, 15.0f});

  // 2 x 2 x 2 m, open towards +Z; each wall a quad facing into the box.
  Shape panel = quad(2.0f, 2.0f);
  w.node("floor", w.mesh("floor", panel, white), {0.0f, 0.0f, 0.0f});
  w.node("ceiling", w.mesh("ceiling", panel, white), {0.0f, 2.0f, 0.0f}, {180.0f, 0.0f, 0.0f});
  w.node("back_wall", w.mesh("back_wall", panel, white), {0.0f, 1.0f, -1.0f}, {90.0f, 0.0f, 0.0f});
  w.node("left_wall_red", w.mesh("left_wall", panel, red), {-1.0f, 1.0f, 0.0f}, {0.0f, 0.0f, -90.0f});
  w.node("right_wall_green", w.mesh("right_wall", panel, green), {1.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 90.0f});
  w.node("light_quad", w.mesh("light", quad(0.5f, 0.5f), light), {0.0f, 1.99f, 0.0f}, {180.0f, 0.0f, 0.0f});
  w.node("tall_box", w.mesh("tall_box", box({0.6f, 1.2f, 0.6f}), white), {-0.35f, 0.6f, -0.3f}, {0.0f, 18.0f, 0.0f});
  w.node("short_box", w.mesh("short_box", box({0.6f, 0.6f, 0.6f}), white), {0.35f, 0.3f, 0.35f}, {0.0f, -17.0f, 0.0f});
  w.camera("front", {0.0f, 1.0f, 3.9f}, {0.0f, 1.0f, 0.0f}, 38.6f);
  w.sky({0.0f, 0.0f, 0.0f});
  w.write(dir);
}

// The white furnace in polished metal: three spheres of white metal (base colour 1,
// metallic 1) at roughness 0 (a mirror), 0.15 and 0.35, apart, under a uniform sky of radiance
// 1. A white metal reflects all it receives at any roughness, so every pixel, sphere, sky or a
// sphere seen in another, is exactly 1: the reflections' estimator and its demodulation add
// and lose nothing.
void metalFurnace(const std::filesystem::path& dir) {
  SceneWriter w("metal_furnace");
  const float roughness[] = {0.0f, 0.15f, 0.35f};
  for (int i = 0; i < 3; ++i) {
    char name[48];
    std::snprintf(name, sizeof name, "white_metal_%03d", int(roughness[i] * 100.0f + 0.5f));
    int m = w.material({name, {1.0f, 1.0f, 1.0f}, 1.0f, roughness[i]});
    w.node(name, w.mesh(name, sphere(0.5f, 160, 80), m), {-1.2f + 1.2f * float(i), 0.0f, float(i % 2) * -0.6f});
  }
  w.camera("front", {0.0f, 0.6f, 3.6f}, {0.0f, 0.0f, -0.2f}, 50.0f);
  w.sky({1.0f, 1.0f, 1.0f});
  w.write(dir);
}

// A mirror floor under a moving box, for the reflections' ghosts: the floor's left half a white
// metal mirror (roughness 0), its right half polished (0.2), a white wall behind, sun and sky.
// A red box stands on the left half until t = 1 s, on the right half from 1 s to 2 s, then
// on the left again (STEP: it jumps), so its reflection leaves one half of the floor for the
// other at once, and whatever a history still shows where it stood is a ghost. (Not a scene to
// compare against the reference: the sun reflected by the mirror onto the wall is a caustic a
// path tracer finds only by chance, and its image is fireflies for thousands of samples.)
void mirrorFloor(const std::filesystem::path& dir) {
  SceneWriter w("mirror_floor");
  int mirror = w.material({"mirror_metal", {0.95f, 0.95f, 0.95f}, 1.0f, 0.0f});
  int polished = w.material({"polished_metal", {0.95f, 0.95f, 0.95f}, 1.0f, 0.2f});
  int plaster = w.material({"white_plaster", {0.8f, 0.8f, 0.78f}, 0.0f, 0.9f});
  int red = w.material({"red_paint", {0.7f, 0.08f, 0.06f}, 0.0f, 0.6f});
  wall(w, "mirror_floor_left", mirror, {-2.0f, -0.05f, 0.0f}, {4.0f, 0.1f, 6.0f});
  wall(w, "polished_floor_right", polished, {2.0f, -0.05f, 0.0f}, {4.0f, 0.1f, 6.0f});
  wall(w, "back_wall", plaster, {0.0f, 1.5f, -3.1f}, {8.0f, 3.0f, 0.2f});
  const glm::vec4 left(-1.5f, 0.4f, -0.5f, 0.0f), right(1.5f, 0.4f, -0.5f, 0.0f);
  const int mover = w.node("moving_box", w.mesh("moving_box", box({0.8f, 0.8f, 0.8f}), red), glm::vec3(left));
  w.nodeChannel("box_jumps", mover, "translation", {0.0f, 1.0f, 2.0f}, {left, right, left}, "STEP");
  w.camera("front", {0.0f, 1.6f, 4.5f}, {0.0f, 0.2f, -0.5f}, 50.0f);
  w.sun({-0.3f, -0.7f, -0.6f}, 4.0f);
  w.sky({0.45f, 0.55f, 0.75f});
  w.write(dir);
}

// The Cornell box made metal, as a new user tries reflections: the floor and both boxes
// polished white metal (base colour 0.95, metallic 1) at `roughness`, the walls as in cornell,
// the ceiling panel lit, and a sun and sky through the open front. Most of what the camera
// sees of the floor and the boxes is the room reflected.
void metalCornell(const std::filesystem::path& dir, const char* name, float roughness) {
  SceneWriter w(name);
  int white = w.material({"cornell_white", {0.73f, 0.73f, 0.73f}, 0.0f, 1.0f});
  int red = w.material({"cornell_red", {0.63f, 0.065f, 0.05f}, 0.0f, 1.0f});
  int green = w.material({"cornell_green", {0.14f, 0.45f, 0.091f}, 0.0f, 1.0f});
  int metal = w.material({"polished_metal", {0.95f, 0.95f, 0.95f}, 1.0f, roughness});
  int light = w.material({"ceiling_light", {0.78f, 0.78f, 0.78f}, 0.0f, 1.0f, {1.0f, 0.85f, 0.6f}, 15.0f});
  Shape panel = quad(2.0f, 2.0f);
  w.node("floor_metal", w.mesh("floor", panel, metal), {0.0f, 0.0f, 0.0f});
  w.node("ceiling", w.mesh("ceiling", panel, white), {0.0f, 2.0f, 0.0f}, {180.0f, 0.0f, 0.0f});
  w.node("back_wall", w.mesh("back_wall", panel, white), {0.0f, 1.0f, -1.0f}, {90.0f, 0.0f, 0.0f});
  w.node("left_wall_red", w.mesh("left_wall", panel, red), {-1.0f, 1.0f, 0.0f}, {0.0f, 0.0f, -90.0f});
  w.node("right_wall_green", w.mesh("right_wall", panel, green), {1.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 90.0f});
  w.node("light_quad", w.mesh("light", quad(0.5f, 0.5f), light), {0.0f, 1.99f, 0.0f}, {180.0f, 0.0f, 0.0f});
  w.node("tall_box_metal", w.mesh("tall_box", box({0.6f, 1.2f, 0.6f}), metal), {-0.35f, 0.6f, -0.3f}, {0.0f, 18.0f, 0.0f});
  w.node("short_box_metal", w.mesh("short_box", box({0.6f, 0.6f, 0.6f}), metal), {0.35f, 0.3f, 0.35f}, {0.0f, -17.0f, 0.0f});
  w.camera("front", {0.0f, 1.0f, 3.9f}, {0.0f, 1.0f, 0.0f}, 38.6f);
  w.sun({0.2f, -0.5f, -0.85f}, 3.0f);
  w.sky({0.35f, 0.4f, 0.5f});
  w.write(dir);
}

// A hall of polished metals: a row of white-metal spheres from a mirror (roughness 0) to 0.5,
// a gold and a copper one, over a floor of dark polished stone (dielectric, roughness 0.1), in
// front of a white wall with an emissive sign, under a sun and sky. Each sphere shows the hall
// through its own lobe: the reflections' sharpness, the seam at the traced roughness and the
// furnace-like energy of white metals are all visible in one view.
void polishedMetals(const std::filesystem::path& dir) {
  SceneWriter w("polished_metals");
  int stone = w.material({"polished_stone", {0.08f, 0.08f, 0.09f}, 0.0f, 0.1f});
  int plaster = w.material({"white_plaster", {0.8f, 0.8f, 0.78f}, 0.0f, 0.9f});
  int sign = w.material({"sign_cyan", {0.05f, 0.05f, 0.05f}, 0.0f, 1.0f, {0.2f, 0.9f, 1.0f}, 8.0f});
  const float roughness[] = {0.0f, 0.05f, 0.1f, 0.2f, 0.3f, 0.4f, 0.5f};
  int sphereMesh = -1;
  for (int i = 0; i < 7; ++i) {
    char name[48];
    std::snprintf(name, sizeof name, "metal_roughness_%03d", int(roughness[i] * 100.0f + 0.5f));
    int m = w.material({name, {0.95f, 0.95f, 0.95f}, 1.0f, roughness[i]});
    sphereMesh = w.mesh(name, sphere(0.45f, 48, 24), m);
    w.node(name, sphereMesh, {-3.0f + float(i), 0.45f, 0.0f});
  }
  int gold = w.material({"gold", {1.0f, 0.78f, 0.34f}, 1.0f, 0.15f});
  int copper = w.material({"copper", {0.95f, 0.64f, 0.54f}, 1.0f, 0.3f});
  w.node("gold_sphere", w.mesh("gold_sphere", sphere(0.6f, 48, 24), gold), {-1.5f, 0.6f, -2.0f});
  w.node("copper_sphere", w.mesh("copper_sphere", sphere(0.6f, 48, 24), copper), {1.5f, 0.6f, -2.0f});
  wall(w, "floor_stone", stone, {0.0f, -0.1f, -1.0f}, {12.0f, 0.2f, 10.0f});
  wall(w, "back_wall", plaster, {0.0f, 2.0f, -4.1f}, {12.0f, 4.0f, 0.2f});
  wall(w, "left_wall", plaster, {-6.1f, 2.0f, -1.0f}, {0.2f, 4.0f, 6.0f});
  wall(w, "sign", sign, {0.0f, 2.6f, -3.95f}, {3.0f, 0.5f, 0.1f});
  w.camera("front", {0.0f, 1.4f, 5.0f}, {0.0f, 0.6f, -1.0f}, 50.0f);
  w.sun({-0.3f, -0.6f, -0.75f}, 6.0f);
  w.sky({0.45f, 0.55f, 0.75f});
  w.write(dir);
}

// A wet street at night, lit by its signs: wet asphalt (dark dielectric, roughness 0.08) with
// mirror puddles of water (IOR 1.33, roughness 0) between two rows of facades whose emissive
// signs (red, cyan, amber, magenta; 6-16 nits) and two warm street lamps (KHR spots) are the
// light; a dark blue night sky, no sun. Most of what the camera sees of the street is the signs
// reflected: what real games show with RT reflections, and what the SH specular cannot (an
// irradiance has no sharp sign in it). The signs are meshes, so the reference reaches them by
// emitter sampling, and the rt path's hits by its emitter samples.
void wetStreet(const std::filesystem::path& dir) {
  SceneWriter w("wet_street");
  int asphalt = w.material({"wet_asphalt", {0.05f, 0.05f, 0.055f}, 0.0f, 0.08f});
  MaterialSpec water{"puddle_water", {0.02f, 0.02f, 0.025f}, 0.0f, 0.0f};
  water.ior = 1.33f;
  int puddle = w.material(water);
  int kerb = w.material({"kerb_concrete", {0.35f, 0.34f, 0.32f}, 0.0f, 0.85f});
  int brick = w.material({"brick", {0.32f, 0.14f, 0.10f}, 0.0f, 0.9f});
  int plaster = w.material({"facade_plaster", {0.55f, 0.52f, 0.48f}, 0.0f, 0.9f});
  int glass = w.material({"dark_window", {0.02f, 0.02f, 0.03f}, 0.0f, 0.05f});
  struct Sign {
    const char* name;
    glm::vec3 colour;
    float nits;
    glm::vec3 center, size;
  };
  const Sign signs[] = {{"sign_red", {1.0f, 0.12f, 0.08f}, 12.0f, {-3.95f, 3.2f, -4.0f}, {0.2f, 0.8f, 2.4f}},
                        {"sign_cyan", {0.15f, 0.85f, 1.0f}, 10.0f, {3.95f, 2.6f, -9.0f}, {0.2f, 1.0f, 3.0f}},
                        {"sign_amber", {1.0f, 0.62f, 0.15f}, 16.0f, {-3.95f, 2.2f, -14.0f}, {0.2f, 0.6f, 2.0f}},
                        {"sign_magenta", {0.95f, 0.2f, 0.85f}, 6.0f, {3.95f, 3.6f, -19.0f}, {0.2f, 1.4f, 1.6f}}};
  for (const Sign& sign : signs) {
    int m = w.material({sign.name, {0.05f, 0.05f, 0.05f}, 0.0f, 1.0f, sign.colour, sign.nits});
    wall(w, sign.name, m, sign.center, sign.size);
  }
  // The street 6 m wide and 30 m long, kerbs and pavements 2 m wide, facades 10 m high.
  wall(w, "street", asphalt, {0.0f, -0.1f, -10.0f}, {6.0f, 0.2f, 30.0f});
  wall(w, "pavement_left", kerb, {-4.0f, 0.0f, -10.0f}, {2.0f, 0.3f, 30.0f});
  wall(w, "pavement_right", kerb, {4.0f, 0.0f, -10.0f}, {2.0f, 0.3f, 30.0f});
  const glm::vec3 puddles[] = {{-1.2f, 0.0f, -3.0f}, {1.0f, 0.0f, -7.5f}, {-0.6f, 0.0f, -12.0f}, {1.4f, 0.0f, -16.5f}};
  const glm::vec3 puddleSize[] = {{1.8f, 0.02f, 1.2f}, {1.4f, 0.02f, 2.0f}, {2.2f, 0.02f, 1.6f}, {1.2f, 0.02f, 1.0f}};
  for (int i = 0; i < 4; ++i) wall(w, "puddle_" + std::to_string(i), puddle, puddles[i], puddleSize[i]);
  for (int i = 0; i < 3; ++i) {
    const float z = -3.0f - 10.0f * float(i);
    wall(w, "facade_left_" + std::to_string(i), i % 2 ? plaster : brick, {-6.0f, 5.0f, z - 2.0f}, {4.0f, 10.0f, 9.6f});
    wall(w, "facade_right_" + std::to_string(i), i % 2 ? brick : plaster, {6.0f, 5.0f, z - 7.0f}, {4.0f, 10.0f, 9.6f});
    wall(w, "window_left_" + std::to_string(i), glass, {-3.95f, 5.5f, z - 1.0f}, {0.1f, 1.6f, 2.4f});
    wall(w, "window_right_" + std::to_string(i), glass, {3.95f, 5.5f, z - 6.0f}, {0.1f, 1.6f, 2.4f});
  }
  w.spotLight("street_lamp_near", {-2.6f, 5.0f, -6.0f}, {0.25f, -1.0f, 0.0f}, 1500.0f, 25.0f, 45.0f,
              {1.0f, 0.75f, 0.45f});
  w.spotLight("street_lamp_far", {2.6f, 5.0f, -17.0f}, {-0.25f, -1.0f, 0.0f}, 1500.0f, 25.0f, 45.0f,
              {1.0f, 0.75f, 0.45f});
  w.camera("street", {0.4f, 1.6f, 4.0f}, {0.0f, 1.2f, -12.0f}, 55.0f);
  w.sky({0.012f, 0.018f, 0.035f});
  w.write(dir);
}

void furnace(const std::filesystem::path& dir) {
  SceneWriter w("furnace");
  int grey = w.material({"furnace_grey", {0.8f, 0.8f, 0.8f}, 0.0f, 1.0f});
  w.node("sphere", w.mesh("sphere", sphere(1.0f, 64, 32), grey), {0.0f, 0.0f, 0.0f});
  w.camera("front", {0.0f, 0.0f, 4.0f}, {0.0f, 0.0f, 0.0f}, 40.0f);
  w.sky({1.0f, 1.0f, 1.0f});
  w.write(dir);
}

// The white furnace: a convex object whose base colour is 1 (roughness 1, dielectric) under a
// uniform sky of radiance 1. An energy-conserving BRDF and a correct renderer show exactly 1 on
// every pixel, whatever the angle and however many bounces: nothing is absorbed, nothing
// created. Finely tessellated so the shading normal stays within ~1.5 degrees of the triangle's
// (a path tracer loses the light that leaves between the two planes: under 0.1% here).
void whiteFurnace(const std::filesystem::path& dir) {
  SceneWriter w("white_furnace");
  int white = w.material({"furnace_white", {1.0f, 1.0f, 1.0f}, 0.0f, 1.0f});
  w.node("sphere", w.mesh("sphere", sphere(1.0f, 160, 80), white), {0.0f, 0.0f, 0.0f});
  w.camera("front", {0.0f, 0.0f, 3.2f}, {0.0f, 0.0f, 0.0f}, 45.0f);
  w.sky({1.0f, 1.0f, 1.0f});
  w.write(dir);
}

// A closed white corridor, 2 x 2.5 x 12 m inside 0.2 m walls, lit only through a door at its
// south end by the sun and the sky: the far end sees light only after many bounces, so a
// bounce cap shows as missing light (the reference's bounce policy is measured here).
void corridor(const std::filesystem::path& dir) {
  SceneWriter w("corridor");
  int white = w.material({"plaster_white", {0.8f, 0.8f, 0.8f}, 0.0f, 1.0f});
  const float t = 0.2f, width = 2.0f, height = 2.5f, length = 12.0f;
  const float zMid = -length / 2;
  wall(w, "floor", white, {0.0f, -t / 2, zMid}, {width + 2 * t, t, length + 2 * t});
  wall(w, "ceiling", white, {0.0f, height + t / 2, zMid}, {width + 2 * t, t, length + 2 * t});
  wall(w, "wall_west", white, {-width / 2 - t / 2, height / 2, zMid}, {t, height, length});
  wall(w, "wall_east", white, {width / 2 + t / 2, height / 2, zMid}, {t, height, length});
  wall(w, "wall_north", white, {0.0f, height / 2, -length - t / 2}, {width, height, t});
  // The south wall around a 0.8 x 2 m door.
  const float door = 0.8f, doorHeight = 2.0f, side = (width - door) / 2;
  wall(w, "wall_south_west", white, {-(door + side) / 2, height / 2, t / 2}, {side, height, t});
  wall(w, "wall_south_east", white, {(door + side) / 2, height / 2, t / 2}, {side, height, t});
  wall(w, "door_lintel", white, {0.0f, (doorHeight + height) / 2, t / 2}, {door, height - doorHeight, t});
  w.camera("inside", {0.0f, 1.5f, -0.6f}, {0.0f, 1.0f, -length}, 60.0f);
  w.sun({0.1f, -0.45f, -1.0f}, 10.0f);
  w.sky({0.6f, 0.75f, 1.0f});
  w.write(dir);
}

// A wall piece given by two opposite corners (metres): the interiors below are laid out by
// their inside faces, and pieces overlap at the corners so no seam line is open to a ray.
void slab(SceneWriter& w, const std::string& name, int material, glm::vec3 lo, glm::vec3 hi) {
  wall(w, name, material, 0.5f * (lo + hi), hi - lo);
}

// A white room (base colour 0.8), 6 x 3 x 8 m inside 0.25 m walls, lit only by the sun (E = 20)
// through a 1 x 2.2 m doorway in its south wall; the sky is black. The sun lands on a floor
// patch by the door; camera 0 stands beside the door looking into the far corner, where no
// surface it sees is sunlit: everything on screen is bounced light, most of it after two or
// more bounces off surfaces behind the camera. Camera 1 looks back at the door.
void doorwayRoom(const std::filesystem::path& dir) {
  SceneWriter w("doorway_room");
  const int white = w.material({"plaster_white", {0.8f, 0.8f, 0.8f}, 0.0f, 1.0f});
  const float t = 0.25f, h = 3.0f, x = 3.0f, z = -8.0f, door = 0.5f, doorTop = 2.2f;
  slab(w, "floor", white, {-x - t, -t, z - t}, {x + t, 0.0f, t});
  slab(w, "ceiling", white, {-x - t, h, z - t}, {x + t, h + t, t});
  slab(w, "wall_west", white, {-x - t, -t, z - t}, {-x, h + t, t});
  slab(w, "wall_east", white, {x, -t, z - t}, {x + t, h + t, t});
  slab(w, "wall_north", white, {-x, -t, z - t}, {x, h + t, z});
  slab(w, "wall_south_west", white, {-x, -t, 0.0f}, {-door, h + t, t});
  slab(w, "wall_south_east", white, {door, -t, 0.0f}, {x, h + t, t});
  slab(w, "door_lintel", white, {-door, doorTop, 0.0f}, {door, h + t, t});
  w.camera("far_corner", {2.2f, 1.6f, -1.2f}, {-2.5f, 2.3f, -7.8f}, 60.0f);
  w.camera("towards_door", {-2.2f, 1.6f, -7.2f}, {0.4f, 0.8f, 0.0f}, 60.0f);
  w.sun({0.15f, -0.75f, -1.0f}, 20.0f);
  w.sky({0.0f, 0.0f, 0.0f});
  w.write(dir);
}

// A long white corridor (base colour 0.8), 2 x 2.5 x 16 m inside 0.2 m walls, closed at both
// ends, lit through four 0.4 m slits across its roof by the sun (E = 20, 58 degrees high: the
// shafts land as strips on the floor and the foot of the east wall) and the sky. The strips
// are small; most of what the cameras see is light bounced along the corridor.
void slitCorridor(const std::filesystem::path& dir) {
  SceneWriter w("slit_corridor");
  const int white = w.material({"plaster_white", {0.8f, 0.8f, 0.8f}, 0.0f, 1.0f});
  const float t = 0.2f, h = 2.5f, x = 1.0f, z = -16.0f, slit = 0.4f;
  slab(w, "floor", white, {-x - t, -t, z - t}, {x + t, 0.0f, t});
  slab(w, "wall_west", white, {-x - t, -t, z - t}, {-x, h + t, t});
  slab(w, "wall_east", white, {x, -t, z - t}, {x + t, h + t, t});
  slab(w, "wall_north", white, {-x, -t, z - t}, {x, h + t, z});
  slab(w, "wall_south", white, {-x, -t, 0.0f}, {x, h + t, t});
  // The roof in five pieces around four slits centred at z = -2, -6, -10, -14.
  float from = t;
  for (int i = 0; i < 4; ++i) {
    const float centre = -2.0f - 4.0f * float(i);
    slab(w, "roof_" + std::to_string(i), white, {-x - t, h, centre + slit / 2}, {x + t, h + t, from});
    from = centre - slit / 2;
  }
  slab(w, "roof_4", white, {-x - t, h, z - t}, {x + t, h + t, from});
  w.camera("down_the_corridor", {0.0f, 1.6f, -0.5f}, {0.0f, 1.2f, z}, 60.0f);
  w.camera("back_from_the_end", {-0.5f, 1.6f, z + 0.5f}, {0.3f, 1.0f, -4.0f}, 60.0f);
  w.sun({0.25f, -0.85f, -0.45f}, 20.0f);
  w.sky({0.6f, 0.75f, 1.0f});
  w.write(dir);
}

// Two white rooms (base colour 0.8), each 4 x 3 x 4 m inside, side by side along x and sharing
// a 0.25 m wall; every wall, floor and roof is 0.25 m thick. The west room is lit by the sun
// (E = 20) and the sky through a 1.2 x 2.2 m doorway in its south wall, the sun landing on its
// floor towards the shared wall; the east room is closed, so its true image is black while the
// sun lights its roof and outer walls. The scene is 8.75 m wide: the legacy path's finest
// voxel at its default resolution (64) is 8.75 * 1.02 / 64 = 0.139 m, so every wall is 1.8
// voxels thick. Camera 0 is in the lit room, camera 1 in the closed room facing the shared wall.
void twinRooms(const std::filesystem::path& dir) {
  SceneWriter w("twin_rooms");
  const int white = w.material({"plaster_white", {0.8f, 0.8f, 0.8f}, 0.0f, 1.0f});
  const float t = 0.25f, h = 3.0f, room = 4.0f, z = -4.0f, half = t / 2;
  const float west = -half - room, east = half + room;  // the rooms' outer inside faces
  slab(w, "floor", white, {west - t, -t, z - t}, {east + t, 0.0f, t});
  slab(w, "roof", white, {west - t, h, z - t}, {east + t, h + t, t});
  slab(w, "wall_north", white, {west - t, -t, z - t}, {east + t, h + t, z});
  slab(w, "wall_west", white, {west - t, -t, z}, {west, h + t, t});
  slab(w, "wall_east", white, {east, -t, z}, {east + t, h + t, t});
  slab(w, "wall_shared", white, {-half, -t, z}, {half, h + t, 0.0f});
  // South: the closed room's wall is whole, the lit room's has a doorway 1.4 to 2.6 m west.
  slab(w, "wall_south_closed", white, {-half, -t, 0.0f}, {east + t, h + t, t});
  const float doorEast = -1.4f, doorWest = -2.6f, doorTop = 2.2f;
  slab(w, "wall_south_lit_east", white, {doorEast, -t, 0.0f}, {-half, h + t, t});
  slab(w, "wall_south_lit_west", white, {west - t, -t, 0.0f}, {doorWest, h + t, t});
  slab(w, "door_lintel", white, {doorWest, doorTop, 0.0f}, {doorEast, h + t, t});
  w.camera("lit_room", {west + 0.5f, 1.6f, -0.6f}, {-half, 1.2f, z + 0.5f}, 60.0f);
  w.camera("closed_room", {east - 0.5f, 1.6f, -0.6f}, {half, 1.3f, z + 1.0f}, 60.0f);
  w.sun({0.45f, -0.6f, -0.65f}, 20.0f);
  w.sky({0.6f, 0.75f, 1.0f});
  w.write(dir);
}

// Node animation: a white room (base colour 0.8), 4 x 3 x 4 m inside 0.25 m walls, with a
// 1.2 x 2.2 m doorway in its south wall and a wooden door hinged on the doorway's west jamb.
// The door is the child of a hinge node whose rotation about +Y the animation drives (4 s
// loop): closed until 1 s, swinging inwards to 90 degrees by 2 s, open until 3 s, closed again
// at 4 s. Outside, a crate slides along x from -3 m to +3 m and back (the same 4 s). The sun
// (E = 20) comes through the doorway onto the floor inside when the door is open; while it is
// closed the room is shut and its true image is black. Camera 0 looks at the front from outside,
// camera 1 at the sunlit floor patch from inside.
void movingDoor(const std::filesystem::path& dir) {
  SceneWriter w("moving_door");
  const int white = w.material({"plaster_white", {0.8f, 0.8f, 0.8f}, 0.0f, 1.0f});
  const int wood = w.material({"door_oak", {0.45f, 0.30f, 0.18f}, 0.0f, 0.7f});
  const int crateWood = w.material({"crate_pine", {0.75f, 0.6f, 0.35f}, 0.0f, 0.8f});
  const float t = 0.25f, h = 3.0f, x = 2.0f, z = -4.0f, door = 0.6f, doorTop = 2.2f;
  slab(w, "ground", white, {-8.0f, -t, z - t}, {8.0f, 0.0f, 8.0f});
  slab(w, "roof", white, {-x - t, h, z - t}, {x + t, h + t, t});
  slab(w, "wall_west", white, {-x - t, 0.0f, z - t}, {-x, h, t});
  slab(w, "wall_east", white, {x, 0.0f, z - t}, {x + t, h, t});
  slab(w, "wall_north", white, {-x, 0.0f, z - t}, {x, h, z});
  slab(w, "wall_south_west", white, {-x, 0.0f, 0.0f}, {-door, h, t});
  slab(w, "wall_south_east", white, {door, 0.0f, 0.0f}, {x, h, t});
  slab(w, "door_lintel", white, {-door, doorTop, 0.0f}, {door, h, t});
  // The hinge sits on the west jamb at mid-wall; the door hangs from it filling the doorway
  // (5 mm short of each jamb and of the lintel, so it swings free).
  const int hinge = w.node("door_hinge", -1, {-door, 0.0f, t / 2});
  const float leaf = 2.0f * door - 0.01f, leafHeight = doorTop - 0.005f, thick = 0.06f;
  w.node("door", w.mesh("door", box({leaf, leafHeight, thick}), wood), {door, leafHeight / 2, 0.0f}, glm::vec3(0.0f),
         glm::vec3(1.0f), hinge);
  const glm::quat shut(1.0f, 0.0f, 0.0f, 0.0f), open = glm::angleAxis(glm::radians(90.0f), glm::vec3(0.0f, 1.0f, 0.0f));
  auto q = [](glm::quat r) { return glm::vec4(r.x, r.y, r.z, r.w); };
  w.nodeChannel("door_and_crate", hinge, "rotation", {0.0f, 1.0f, 2.0f, 3.0f, 4.0f},
                {q(shut), q(shut), q(open), q(open), q(shut)});
  const int crate = w.node("crate", w.mesh("crate", box({0.6f, 0.6f, 0.6f}), crateWood), {-3.0f, 0.3f, 2.5f});
  w.nodeChannel("door_and_crate", crate, "translation", {0.0f, 2.0f, 4.0f},
                {{-3.0f, 0.3f, 2.5f, 0.0f}, {3.0f, 0.3f, 2.5f, 0.0f}, {-3.0f, 0.3f, 2.5f, 0.0f}});
  w.camera("outside", {0.0f, 1.7f, 7.5f}, {0.0f, 1.0f, 0.0f}, 60.0f);
  w.camera("inside", {1.5f, 1.6f, -3.5f}, {0.0f, 0.0f, -1.5f}, 60.0f);
  w.sun({0.15f, -0.6f, -1.0f}, 20.0f);
  w.sky({0.6f, 0.75f, 1.0f});
  w.write(dir);
}

// Skinning: a box figure 1.83 m tall walking along +x. One mesh (torso, head, legs and
// arms, 120 vertices) skinned to five joints: hips, two legs, two arms; each part follows its
// joint with weight 1 except the legs' top vertices, shared half and half with the hips. The
// legs swing +-30 degrees about z once a second in opposition, the arms +-20 degrees against
// them, and the figure's root walks from x = -2 m to +2 m in 4 s (the loop). Camera 0 looks
// at it from the side.
void walker(const std::filesystem::path& dir) {
  SceneWriter w("walker");
  const int ground = w.material({"ground", {0.7f, 0.7f, 0.7f}, 0.0f, 0.9f});
  const int cloth = w.material({"walker_cloth", {0.2f, 0.35f, 0.7f}, 0.0f, 0.8f});
  w.node("ground", w.mesh("ground", quad(12.0f, 12.0f, 2.0f), ground), {0.0f, 0.0f, 0.0f});
  // The skeleton in its bind pose (the root at the origin): joint positions in metres.
  const glm::vec3 hipsAt(0.0f, 0.95f, 0.0f), legAt(0.0f, 0.0f, 0.1f), armAt(0.0f, 0.6f, 0.25f);
  const int root = w.node("walker", -1, glm::vec3(0.0f));
  const int hips = w.node("hips", -1, hipsAt, glm::vec3(0.0f), glm::vec3(1.0f), root);
  const int legLeft = w.node("leg_left", -1, legAt, glm::vec3(0.0f), glm::vec3(1.0f), hips);
  const int legRight = w.node("leg_right", -1, -legAt, glm::vec3(0.0f), glm::vec3(1.0f), hips);
  const int armLeft = w.node("arm_left", -1, armAt, glm::vec3(0.0f), glm::vec3(1.0f), hips);
  const int armRight = w.node("arm_right", -1, armAt * glm::vec3(1.0f, 1.0f, -1.0f), glm::vec3(0.0f), glm::vec3(1.0f), hips);
  // Joint order in the skin: 0 hips, 1 left leg, 2 right leg, 3 left arm, 4 right arm.
  const std::vector<glm::vec3> bindPositions = {hipsAt, hipsAt + legAt, hipsAt - legAt, hipsAt + armAt,
                                                hipsAt + armAt * glm::vec3(1.0f, 1.0f, -1.0f)};
  std::vector<glm::mat4> inverseBind;
  for (const glm::vec3& p : bindPositions) inverseBind.push_back(glm::translate(glm::mat4(1.0f), -p));
  auto part = [](glm::vec3 size, glm::vec3 centre, uint32_t joint) {
    Shape s = transformed(box(size), glm::translate(glm::mat4(1.0f), centre));
    return s.boundTo(joint);
  };
  Shape body = part({0.3f, 0.6f, 0.4f}, {0.0f, 1.25f, 0.0f}, 0);
  body.append(part({0.22f, 0.22f, 0.22f}, {0.0f, 1.72f, 0.0f}, 0));
  for (uint32_t side = 0; side < 2; ++side) {
    const float z = side == 0 ? 0.1f : -0.1f;
    Shape leg = part({0.14f, 0.95f, 0.14f}, {0.0f, 0.475f, z}, 1 + side);
    // The hip end bends with the hips as much as with the leg.
    for (size_t v = 0; v < leg.positions.size(); ++v)
      if (leg.positions[v].y > 0.9f) {
        leg.joints[v] = glm::uvec4(1 + side, 0, 0, 0);
        leg.weights[v] = glm::vec4(0.5f, 0.5f, 0.0f, 0.0f);
      }
    body.append(leg);
    body.append(part({0.1f, 0.65f, 0.1f}, {0.0f, 1.25f, side == 0 ? 0.25f : -0.25f}, 3 + side));
  }
  const int bodyNode = w.node("walker_body", w.mesh("walker_body", body, cloth), glm::vec3(0.0f), glm::vec3(0.0f),
                              glm::vec3(1.0f), root);
  w.skinNode(bodyNode, w.skin("walker_skin", {hips, legLeft, legRight, armLeft, armRight}, inverseBind));
  std::vector<float> times;
  std::vector<glm::vec4> legL, legR, armL, armR;
  auto aboutZ = [](float degrees) {
    const glm::quat q = glm::angleAxis(glm::radians(degrees), glm::vec3(0.0f, 0.0f, 1.0f));
    return glm::vec4(q.x, q.y, q.z, q.w);
  };
  for (int k = 0; k <= 32; ++k) {
    const float t = 0.125f * float(k), swing = std::sin(6.2831853f * t);
    times.push_back(t);
    legL.push_back(aboutZ(30.0f * swing));
    legR.push_back(aboutZ(-30.0f * swing));
    armL.push_back(aboutZ(-20.0f * swing));
    armR.push_back(aboutZ(20.0f * swing));
  }
  w.nodeChannel("walk", legLeft, "rotation", times, legL);
  w.nodeChannel("walk", legRight, "rotation", times, legR);
  w.nodeChannel("walk", armLeft, "rotation", times, armL);
  w.nodeChannel("walk", armRight, "rotation", times, armR);
  w.nodeChannel("walk", root, "translation", {0.0f, 4.0f}, {{-2.0f, 0.0f, 0.0f, 0.0f}, {2.0f, 0.0f, 0.0f, 0.0f}});
  w.camera("side", {0.0f, 1.2f, 6.0f}, {0.0f, 0.9f, 0.0f}, 50.0f);
  w.sun({0.3f, -0.8f, -0.5f}, 10.0f);
  w.sky({0.6f, 0.75f, 1.0f});
  w.write(dir);
}

// A closed 2 m box whose six walls (base colour 0.8) all emit radiance 0.2, seen from inside:
// with Lambertian walls (the diffuse and clay override modes) the radiance is the same
// everywhere, L = Le / (1 - rho) = 1.
void closedBox(const std::filesystem::path& dir) {
  SceneWriter w("closed_box");
  // Seen from inside: the box's faces point out, so the file says it is double-sided (glTF culls
  // the back of a single-sided surface for the camera).
  MaterialSpec glowingSpec{"glowing_white", {0.8f, 0.8f, 0.8f}, 0.0f, 1.0f, {1.0f, 1.0f, 1.0f}, 0.2f};
  glowingSpec.doubleSided = true;
  int glowing = w.material(glowingSpec);
  w.node("box", w.mesh("box", box({2.0f, 2.0f, 2.0f}), glowing), {0.0f, 0.0f, 0.0f});
  w.camera("inside", {0.0f, 0.0f, 0.5f}, {0.0f, 0.0f, -1.0f}, 70.0f);
  w.sky({0.0f, 0.0f, 0.0f});
  w.write(dir);
}

void plane(const std::filesystem::path& dir) {
  SceneWriter w("plane");
  int grey = w.material({"ground_grey", {0.8f, 0.8f, 0.8f}, 0.0f, 1.0f});
  w.node("ground", w.mesh("ground", quad(100.0f, 100.0f, 0.5f), grey), {0.0f, 0.0f, 0.0f});
  w.camera("down45", {0.0f, 3.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, 60.0f);
  w.sky({1.0f, 1.0f, 1.0f});
  w.write(dir);
}

// Fireflies on purpose: a ground under a uniform sky and, 0.3 m above it, five 2 cm sparks
// facing down whose radiance is 1e4 (emissive strength). A ground pixel's ray finds one with
// a probability near 1e-4 and then brings 1e4 times the sky: a few pixels a frame, and
// about a third of the ground's light on average. The denoiser's hard case.
void sparks(const std::filesystem::path& dir) {
  SceneWriter w("sparks");
  int grey = w.material({"ground_grey", {0.8f, 0.8f, 0.8f}, 0.0f, 1.0f});
  int spark = w.material({"spark", {0.0f, 0.0f, 0.0f}, 0.0f, 1.0f, {1.0f, 0.9f, 0.7f}, 1.0e4f});
  w.node("ground", w.mesh("ground", quad(20.0f, 20.0f, 0.5f), grey), {0.0f, 0.0f, 0.0f});
  int sparkMesh = w.mesh("spark", quad(0.02f, 0.02f), spark);
  const glm::vec3 at[] = {{0.0f, 0.3f, 0.0f}, {-0.8f, 0.3f, 0.4f}, {0.7f, 0.3f, -0.5f}, {0.3f, 0.3f, 0.8f},
                          {-0.5f, 0.3f, -0.7f}};
  for (int i = 0; i < 5; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "spark_%d", i + 1);
    w.node(name, sparkMesh, at[i], {180.0f, 0.0f, 0.0f});
  }
  w.camera("down45", {0.0f, 2.0f, 2.0f}, {0.0f, 0.0f, 0.0f}, 60.0f);
  w.sky({1.0f, 1.0f, 1.0f});
  w.write(dir);
}

// Many instances for the RT module's culling: a 100 x 100 grid of crates (10,000 instances of
// two meshes) on a 220 m ground. The camera stands at a corner looking out, so it sees few.
void grove(const std::filesystem::path& dir) {
  SceneWriter w("grove");
  int ground = w.material({"grass", {0.25f, 0.35f, 0.15f}, 0.0f, 0.9f});
  int wood = w.material({"crate_wood", {0.55f, 0.40f, 0.25f}, 0.0f, 0.8f});
  int stone = w.material({"crate_stone", {0.60f, 0.60f, 0.58f}, 0.0f, 0.7f});
  w.node("ground", w.mesh("ground", quad(220.0f, 220.0f, 1.0f), ground), {0.0f, 0.0f, 0.0f});
  int crate = w.mesh("crate", box({1.0f, 1.0f, 1.0f}), wood);
  int pillar = w.mesh("pillar", box({0.6f, 2.0f, 0.6f}), stone);
  for (int z = 0; z < 100; ++z)
    for (int x = 0; x < 100; ++x) {
      char name[32];
      std::snprintf(name, sizeof name, "item_%02d_%02d", z, x);
      const bool isPillar = (x * 7 + z * 3) % 5 == 0;
      w.node(name, isPillar ? pillar : crate, {-99.0f + 2.0f * float(x), isPillar ? 1.0f : 0.5f, -99.0f + 2.0f * float(z)},
             {0.0f, float((x * 37 + z * 11) % 90), 0.0f});
    }
  w.camera("corner_out", {-100.5f, 1.7f, -100.5f}, {-110.0f, 1.0f, -108.0f}, 60.0f);
  w.camera("overview", {-110.0f, 40.0f, -110.0f}, {0.0f, 0.0f, 0.0f}, 50.0f);
  w.sun({0.3f, -0.7f, 0.4f}, 20.0f);
  w.sky({0.6f, 0.75f, 1.0f});
  w.write(dir);
}

// Deforming meshes for the RT module's BLAS refits: 48 cloth banners (a 1 x 2 m grid of
// 8 x 16 quads each) hang in rows in a walled yard, each swaying and rippling through two
// morph targets driven by its own animation channel (a phase per banner, 2 s loop). They
// share one mesh in the file; the importer gives each node its own copy.
void banners(const std::filesystem::path& dir) {
  SceneWriter w("banners");
  int ground = w.material({"flagstones", {0.55f, 0.53f, 0.50f}, 0.0f, 0.85f});
  int plaster = w.material({"plaster_ochre", {0.75f, 0.55f, 0.25f}, 0.0f, 0.9f});
  int cloth = w.material({"banner_red", {0.70f, 0.12f, 0.10f}, 0.0f, 0.95f});
  int wood = w.material({"pole_wood", {0.35f, 0.25f, 0.15f}, 0.0f, 0.8f});
  w.node("ground", w.mesh("ground", quad(30.0f, 30.0f, 2.0f), ground), {0.0f, 0.0f, 0.0f});
  w.node("wall_back", w.mesh("wall_back", box({30.0f, 5.0f, 0.4f}), plaster), {0.0f, 2.5f, -15.0f});
  w.node("wall_left", w.mesh("wall_left", box({0.4f, 5.0f, 30.0f}), plaster), {-15.0f, 2.5f, 0.0f});

  // The banner: a grid in XY hanging from its top edge at y = 0 beside its pole, facing +Z.
  const int cols = 8, rows = 16;
  const float width = 1.0f, height = 2.0f;
  Shape banner;
  for (int r = 0; r <= rows; ++r)
    for (int c = 0; c <= cols; ++c) {
      banner.positions.push_back({0.06f + width * float(c) / cols, -height * float(r) / rows, 0.0f});
      banner.normals.push_back({0.0f, 0.0f, 1.0f});
      banner.uvs.push_back({float(c) / cols, float(r) / rows});
    }
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      uint32_t a = uint32_t(r * (cols + 1) + c), b = a + 1, d = a + uint32_t(cols + 1), e = d + 1;
      banner.indices.insert(banner.indices.end(), {a, d, b, b, d, e});
    }
  // Two-sided: the back face as well, so rays and the raster see the cloth from both sides.
  Shape back = banner;
  for (auto& n : back.normals) n = -n;
  for (size_t i = 0; i < back.indices.size(); i += 3) std::swap(back.indices[i + 1], back.indices[i + 2]);
  const uint32_t frontVertices = uint32_t(banner.positions.size());
  banner.append(back);
  // Target 0 sways the cloth out along +Z, more towards the bottom; target 1 ripples it across.
  std::vector<glm::vec3> sway, ripple, swayN, rippleN;
  for (size_t v = 0; v < banner.positions.size(); ++v) {
    const glm::vec3 p = banner.positions[v];
    const float down = -p.y / height, across = (p.x - 0.06f) / width;
    const float sign = v < frontVertices ? 1.0f : -1.0f;
    sway.push_back({0.0f, 0.1f * down * down, 0.6f * down * down});
    ripple.push_back({0.0f, 0.0f, 0.15f * down * std::sin(6.2831853f * across)});
    // The normals' change: the surface tilts by the deltas' slopes (small-angle).
    swayN.push_back(sign * glm::vec3(0.0f, 0.6f * down, 0.0f));
    rippleN.push_back(sign * glm::vec3(-0.15f * down * 6.2831853f * std::cos(6.2831853f * across) / width, 0.0f, 0.0f));
  }
  int bannerMesh = w.mesh("banner", banner, cloth);
  w.morphTargets(bannerMesh, {sway, ripple}, {swayN, rippleN}, {0.0, 0.0});
  int pole = w.mesh("pole", cylinder(0.05f, 3.2f, 8), wood);
  const int keys = 25;
  const float seconds = 2.0f;
  int index = 0;
  for (int row = 0; row < 6; ++row)
    for (int k = 0; k < 8; ++k, ++index) {
      const glm::vec3 at(-10.0f + 2.6f * float(k), 3.0f, -11.0f + 3.8f * float(row));
      char name[32];
      std::snprintf(name, sizeof name, "banner_%d_%d", row, k);
      int node = w.node(name, bannerMesh, at);
      std::snprintf(name, sizeof name, "pole_%d_%d", row, k);
      w.node(name, pole, at - glm::vec3(0.0f, 3.0f, 0.0f));
      std::vector<float> times, weights;
      const float phase = 0.7f * float(index);
      for (int t = 0; t < keys; ++t) {
        const float time = seconds * float(t) / float(keys - 1), angle = 6.2831853f * time / seconds + phase;
        times.push_back(time);
        weights.push_back(0.5f + 0.5f * std::sin(angle));
        weights.push_back(std::sin(2.0f * angle));
      }
      w.weightsChannel("wind", node, times, weights);
    }
  w.camera("along_rows", {9.0f, 2.2f, 8.0f}, {-4.0f, 1.5f, -6.0f}, 55.0f);
  w.sun({-0.35f, -0.6f, -0.7f}, 20.0f);
  w.sky({0.6f, 0.75f, 1.0f});
  w.write(dir);
}

// An interior lit only by lamps: a closed 6 x 3 x 5 m room (0.2 m walls, no window, black sky)
// with a table, a cabinet and a sphere, two warm point lights (bulbs of about 1000 lm: 80 cd)
// and a spot light (400 cd, cone 20/30 degrees) on the sphere. Every path's local lights, their
// shadows and their bounce light are measured here (docs/accuracy.md).
void lamps(const std::filesystem::path& dir) {
  SceneWriter w("lamps");
  int plaster = w.material({"plaster_white", {0.80f, 0.78f, 0.74f}, 0.0f, 0.9f});
  int floorMat = w.material({"floor_oak", {0.45f, 0.30f, 0.18f}, 0.0f, 0.6f});
  int blue = w.material({"cabinet_blue", {0.15f, 0.25f, 0.55f}, 0.0f, 0.7f});
  int wood = w.material({"table_wood", {0.55f, 0.38f, 0.22f}, 0.0f, 0.7f});
  int copper = w.material({"copper", {0.95f, 0.64f, 0.54f}, 1.0f, 0.35f});
  closedRoom(w, floorMat, plaster, 6.0f, 5.0f, 3.0f, 0.2f);
  table(w, wood, -0.8f, -0.6f, 1.6f, 0.9f, 0.7f, 0.38f);
  wall(w, "cabinet", blue, {2.3f, 0.9f, -1.9f}, {1.0f, 1.8f, 0.6f});
  w.node("copper_sphere", w.mesh("sphere", sphere(0.4f, 48, 24), copper), {1.2f, 0.4f, 0.6f});
  w.pointLight("bulb_table", {-0.8f, 1.6f, -0.6f}, 80.0f, {1.0f, 0.78f, 0.55f});
  w.pointLight("bulb_corner", {-2.4f, 2.6f, 1.9f}, 80.0f, {1.0f, 0.85f, 0.7f}, 10.0f);
  w.spotLight("spot_sphere", {1.2f, 2.9f, 0.6f}, {0.0f, -1.0f, 0.0f}, 400.0f, 20.0f, 30.0f);
  w.camera("room_view", {2.6f, 1.7f, 2.3f}, {-0.6f, 0.8f, -1.0f}, 60.0f);
  w.sky({0.0f, 0.0f, 0.0f});
  w.write(dir);
}

// Area lights (the lighting sidecar's rect, disk and tube: glTF has no area lights): a closed
// 5 x 3 x 4 m white room (0.2 m walls, black sky, no sun) with a table and a copper sphere, lit
// only by a 1.2 x 0.6 m ceiling panel of 1500 nits, a 0.25 m disk downlight of 3000 nits and a
// 1.2 m tube (2 cm radius) on the west wall, all in area_room.lighting.json (`--lighting`).
// Soft shadows, penumbrae under the table and glossy reflections of the panel in the sphere.
void areaRoom(const std::filesystem::path& dir) {
  SceneWriter w("area_room");
  int plaster = w.material({"plaster_white", {0.80f, 0.80f, 0.80f}, 0.0f, 0.9f});
  int floorMat = w.material({"floor_grey", {0.50f, 0.50f, 0.50f}, 0.0f, 0.4f});
  int wood = w.material({"table_wood", {0.55f, 0.38f, 0.22f}, 0.0f, 0.7f});
  int copper = w.material({"copper", {0.95f, 0.64f, 0.54f}, 1.0f, 0.25f});
  closedRoom(w, floorMat, plaster, 5.0f, 4.0f, 3.0f, 0.2f);
  table(w, wood, -0.5f, -0.4f, 1.4f, 0.8f, 0.62f, 0.33f);
  w.node("copper_sphere", w.mesh("sphere", sphere(0.35f, 48, 24), copper), {1.3f, 0.35f, 0.5f});
  w.camera("room_view", {2.2f, 1.7f, 1.8f}, {-0.6f, 0.7f, -0.8f}, 60.0f);
  w.sky({0.0f, 0.0f, 0.0f});
  w.write(dir);
  // The sidecar: what `--lighting` reads (session/lighting_file.h), intensities in nits.
  writeLightingSidecar(dir / "area_room.lighting.json", R"({
  "format": "twinlight.lighting",
  "version": 1,
  "sun": {"direction": [0.3, -1, 0.2], "irradiance": 0},
  "sky": {"radiance": 0},
  "exposure_ev": null,
  "environment": null,
  "lights": [
    {"name": "ceiling_panel", "type": "rect", "position": [-0.5, 2.99, -0.4], "direction": [0, -1, 0], "width_axis": [1, 0, 0],
     "width": 1.2, "height": 0.6, "temperature_k": 4000, "intensity": 1500},
    {"name": "downlight", "type": "disk", "position": [1.3, 2.99, 0.5], "direction": [0, -1, 0], "radius": 0.25,
     "temperature_k": 3000, "intensity": 3000},
    {"name": "wall_tube", "type": "tube", "position": [-2.4, 2.0, 0.0], "direction": [0, 0, 1], "radius": 0.02, "length": 1.2,
     "temperature_k": 2700, "intensity": 20000}
  ]
}
)");
}

// The lamps room with one area light more: a 0.8 x 0.4 m ceiling panel of 2000 nits over the
// table, beside the file's two bulbs and spot, in lamps_with_panel.lighting.json (`--lighting`;
// not named lamps.lighting.json, so the editor does not read it for lamps.gltf by itself). The
// interior lit by the light table: point, spot and area lights together.
void lampsWithPanel(const std::filesystem::path& dir) {
  writeLightingSidecar(dir / "lamps_with_panel.lighting.json", R"({
  "format": "twinlight.lighting",
  "version": 1,
  "sun": {"direction": [0.3, -1, 0.2], "irradiance": 0},
  "sky": {"radiance": 0},
  "exposure_ev": null,
  "environment": null,
  "lights": [
    {"name": "bulb_table", "type": "point", "position": [-0.8, 1.6, -0.6], "color": [1.0, 0.78, 0.55], "intensity": 80},
    {"name": "bulb_corner", "type": "point", "position": [-2.4, 2.6, 1.9], "color": [1.0, 0.85, 0.7], "intensity": 80,
     "range": 10},
    {"name": "spot_sphere", "type": "spot", "position": [1.2, 2.9, 0.6], "direction": [0, -1, 0], "intensity": 400,
     "inner_cone_deg": 20, "outer_cone_deg": 30},
    {"name": "ceiling_panel", "type": "rect", "position": [-0.8, 2.99, -0.6], "direction": [0, -1, 0], "width_axis": [1, 0, 0],
     "width": 0.8, "height": 0.4, "temperature_k": 4000, "intensity": 2000}
  ]
}
)");
}

}  // namespace

// An equirectangular sky for the HDRI-lit exterior (radiance on Twinlight's scale, row 0 at the
// zenith): a blue zenith fading to a pale horizon, a warm grey ground below it, and a sun disc of
// 2 degrees radius at 35 degrees elevation whose texels give an irradiance of about 8 on a
// surface facing it (a real sun's share against its sky: E_sun / (pi L_sky) about 4). 256 x 128
// float texels, zip-compressed.
void writeCourtyardSky(const std::filesystem::path& file) {
  const int w = 256, h = 128;
  const double pi = 3.14159265358979323846;
  const glm::dvec3 toSun = glm::normalize(glm::dvec3(std::cos(glm::radians(35.0)) * std::sin(glm::radians(40.0)),
                                                     std::sin(glm::radians(35.0)),
                                                     std::cos(glm::radians(35.0)) * std::cos(glm::radians(40.0))));
  const double sunRadius = glm::radians(2.0), sunSolidAngle = 2.0 * pi * (1.0 - std::cos(sunRadius));
  const double sunRadiance = 8.0 / sunSolidAngle;
  std::vector<float> px(size_t(w) * h * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      // The texel's centre direction as the environment map reads it (shared/environment.h
      // tlEquirectDirection): theta = pi v from +Y, phi = 2 pi u.
      const double theta = pi * (y + 0.5) / h, phi = 2.0 * pi * (x + 0.5) / w;
      const glm::dvec3 d(-std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi));
      glm::dvec3 L;
      if (d.y >= 0.0) {
        const double t = std::pow(1.0 - d.y, 3.0);  // 0 at the zenith, 1 at the horizon
        L = glm::mix(glm::dvec3(0.18, 0.32, 0.75), glm::dvec3(0.85, 0.9, 1.0), t);
      } else {
        L = glm::dvec3(0.22, 0.19, 0.15);
      }
      if (std::acos(std::clamp(glm::dot(d, toSun), -1.0, 1.0)) < sunRadius) L = glm::dvec3(1.0, 0.93, 0.82) * sunRadiance;
      for (int c = 0; c < 3; ++c) px[(size_t(y) * w + x) * 3 + c] = float(L[c]);
    }
  std::filesystem::create_directories(file.parent_path());
  auto out = OIIO::ImageOutput::create(file.string());
  OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::FLOAT);
  spec.attribute("compression", "zip");
  // A fixed date: OpenEXR otherwise stamps the time of writing, and the generator's output has to
  // be the same file every run (cli.content_is_generated).
  spec.attribute("DateTime", "2026:12:03 00:00:00");
  if (!out || !out->open(file.string(), spec) || !out->write_image(OIIO::TypeDesc::FLOAT, px.data()) || !out->close())
    throw std::runtime_error("cannot write " + file.string());
}

namespace {

// The HDRI-lit exterior: a 30 m grey paved ground with a white wall, two boxes, a column, an
// arch and a copper sphere, lit by environments/courtyard_sky.exr alone (no glTF sun; the map's
// sun disc casts the shadows), set up in courtyard.lighting.json beside it, which the editor reads
// when it opens the scene and `--lighting` gives the command line.
void courtyard(const std::filesystem::path& dir) {
  SceneWriter w("courtyard");
  int paving = w.material({"paving", {0.45f, 0.43f, 0.40f}, 0.0f, 0.8f});
  int white = w.material({"limewash", {0.80f, 0.78f, 0.72f}, 0.0f, 0.9f});
  int red = w.material({"terracotta", {0.62f, 0.24f, 0.14f}, 0.0f, 0.7f});
  int copper = w.material({"copper", {0.95f, 0.64f, 0.54f}, 1.0f, 0.3f});
  w.node("ground", w.mesh("ground", quad(30.0f, 30.0f), paving), {0.0f, 0.0f, 0.0f});
  wall(w, "back_wall", white, {0.0f, 1.5f, -3.0f}, {8.0f, 3.0f, 0.3f});
  wall(w, "box_large", red, {-2.0f, 0.5f, -0.8f}, {1.0f, 1.0f, 1.0f});
  wall(w, "box_small", white, {-0.8f, 0.3f, 0.4f}, {0.6f, 0.6f, 0.6f});
  wall(w, "column", white, {2.2f, 1.25f, -1.2f}, {0.4f, 2.5f, 0.4f});
  wall(w, "arch_left", white, {0.2f, 1.0f, -1.8f}, {0.3f, 2.0f, 0.3f});
  wall(w, "arch_right", white, {1.4f, 1.0f, -1.8f}, {0.3f, 2.0f, 0.3f});
  wall(w, "arch_top", white, {0.8f, 2.15f, -1.8f}, {1.5f, 0.3f, 0.3f});
  w.node("copper_sphere", w.mesh("sphere", sphere(0.45f, 48, 24), copper), {1.0f, 0.45f, 0.6f});
  w.camera("court_view", {3.6f, 1.8f, 4.4f}, {-0.2f, 0.7f, -1.0f}, 55.0f);
  w.sky({0.0f, 0.0f, 0.0f});
  w.write(dir);
  writeCourtyardSky(dir / "environments" / "courtyard_sky.exr");
  writeLightingSidecar(dir / "courtyard.lighting.json", R"({
  "format": "twinlight.lighting",
  "version": 1,
  "sun": {"direction": [0.3, -1, 0.2], "irradiance": 0},
  "sky": {"radiance": 0},
  "exposure_ev": null,
  "environment": {"file": "environments/courtyard_sky.exr", "rotation_deg": 0, "intensity": 1},
  "lights": []
}
)");
}

// Many lights: 256 point lights (a 16 x 16 grid, 0.5 m apart, 0.8 to 2.3 m up, 8 to 68 cd,
// four colours) over a 20 m grey ground under a black sky, seen from above at an angle. For the
// light table's many-light sampling: its noise, its convergence and its cost against the count.
void lampGrid(const std::filesystem::path& dir) {
  SceneWriter w("lamp_grid");
  int grey = w.material({"ground_grey", {0.8f, 0.8f, 0.8f}, 0.0f, 1.0f});
  wall(w, "ground", grey, {0.0f, -0.1f, 0.0f}, {20.0f, 0.2f, 20.0f});
  const glm::vec3 colours[4] = {{1.0f, 0.8f, 0.6f}, {0.6f, 0.8f, 1.0f}, {1.0f, 1.0f, 1.0f}, {0.8f, 1.0f, 0.7f}};
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j) {
      char name[32];
      std::snprintf(name, sizeof name, "lamp_%02d_%02d", i, j);
      const float x = -3.75f + 0.5f * float(i), z = -3.75f + 0.5f * float(j);
      w.pointLight(name, {x, 0.8f + 0.1f * float((i * 7 + j * 3) % 16), z}, 8.0f + 4.0f * float((i * 5 + j * 11) % 16),
                   colours[(i + 2 * j) % 4]);
    }
  w.camera("above", {0.0f, 6.0f, 6.0f}, {0.0f, 0.0f, 0.0f}, 60.0f);
  w.sky({0.0f, 0.0f, 0.0f});
  w.write(dir);
}

// Textures as .glb exports carry them: images inside the binary (bufferViews), one 8-bit PNG
// base colour and one 16-bit PNG emissive whose texel, 128/65535, is 1.5e-4 after sRGB
// decoding: times the emissive strength 1e4 the right quad glows with radiance 1.51, which an
// importer that cuts 16 bits to 8 shows as 0. Two 1 m quads facing the camera, no light.
void embeddedTextures(const std::filesystem::path& dir) {
  SceneWriter w("embedded_textures");
  w.binary();
  const std::vector<float> base = {188 / 255.0f, 94 / 255.0f, 47 / 255.0f};
  std::vector<float> baseTexels;
  for (int i = 0; i < 4; ++i) baseTexels.insert(baseTexels.end(), base.begin(), base.end());
  const int baseTexture = w.embeddedTexture("base_8bit", encodeImage("png", 2, 2, 3, baseTexels, 8), "image/png");
  const std::vector<float> emissiveTexels(2 * 2 * 3, 128.0f / 65535.0f);
  const int emissiveTexture =
      w.embeddedTexture("emissive_16bit", encodeImage("png", 2, 2, 3, emissiveTexels, 16), "image/png");
  MaterialSpec baseSpec{"base_colour_8bit", {1.0f, 1.0f, 1.0f}, 0.0f, 1.0f};
  baseSpec.baseColorTextureIndex = baseTexture;
  MaterialSpec emissiveSpec{"emissive_16bit", {0.0f, 0.0f, 0.0f}, 0.0f, 1.0f, {1.0f, 1.0f, 1.0f}, 1.0e4f};
  emissiveSpec.emissiveTextureIndex = emissiveTexture;
  const Shape panel = quad(1.0f, 1.0f);
  w.node("base_colour_quad", w.mesh("base_colour_quad", panel, w.material(baseSpec)), {-0.55f, 0.0f, 0.0f},
         {90.0f, 0.0f, 0.0f});
  w.node("emissive_quad", w.mesh("emissive_quad", panel, w.material(emissiveSpec)), {0.55f, 0.0f, 0.0f},
         {90.0f, 0.0f, 0.0f});
  w.camera("front", {0.0f, 0.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, 40.0f);
  w.sky({0.0f, 0.0f, 0.0f});
  w.write(dir);
}

std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t b0 = bytes[i], b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0u, b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0u;
    const uint32_t v = (b0 << 16) | (b1 << 8) | b2;
    out += digits[(v >> 18) & 63];
    out += digits[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? digits[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? digits[v & 63] : '=';
  }
  return out;
}

// Tangent space as glTF specifies it: four 1 m quads on the ground (normal +Y) share one
// normal map (a data: URI) whose every texel is the tangent-space normal (0.3, 0.5, 0.81).
// The map's green axis points to the image's top, which is decreasing v, so on each quad the
// bump leans towards -dP/dv = +Z and its red axis along the tangent dP/du: +X on the plain
// quads, -X where u is mirrored. Two quads carry TANGENT as an exporter writes it (w = -1 on
// the plain quad: the bitangent w * cross(N, T) = +Z), two leave it to the importer; all four
// must lean the same way (tests/gpu/test_gltf_probes.cpp).
void normalProbe(const std::filesystem::path& dir) {
  SceneWriter w("normal_probe");
  const glm::vec3 tn = glm::normalize(glm::vec3(0.3f, 0.5f, 0.81f));
  std::vector<float> texels;
  for (int i = 0; i < 4 * 4; ++i)
    for (int c = 0; c < 3; ++c) texels.push_back(std::round((tn[c] * 0.5f + 0.5f) * 255.0f) / 255.0f);
  const int normalTexture =
      w.dataUriTexture("tilted_normal", "data:image/png;base64," + base64(encodeImage("png", 4, 4, 3, texels, 8)));
  MaterialSpec spec{"normal_mapped", {0.8f, 0.8f, 0.8f}, 0.0f, 0.6f};
  spec.normalTextureIndex = normalTexture;
  const int material = w.material(spec);
  Shape plain = quad(1.0f, 1.0f);
  Shape mirrored = plain;
  for (auto& uv : mirrored.uvs) uv.x = 1.0f - uv.x;
  Shape plainTangents = plain, mirroredTangents = mirrored;
  plainTangents.tangents.assign(plain.positions.size(), glm::vec4(1.0f, 0.0f, 0.0f, -1.0f));
  mirroredTangents.tangents.assign(mirrored.positions.size(), glm::vec4(-1.0f, 0.0f, 0.0f, 1.0f));
  w.node("plain_generated", w.mesh("plain_generated", plain, material), {-1.65f, 0.0f, 0.0f});
  w.node("plain_supplied", w.mesh("plain_supplied", plainTangents, material), {-0.55f, 0.0f, 0.0f});
  w.node("mirrored_generated", w.mesh("mirrored_generated", mirrored, material), {0.55f, 0.0f, 0.0f});
  w.node("mirrored_supplied", w.mesh("mirrored_supplied", mirroredTangents, material), {1.65f, 0.0f, 0.0f});
  w.camera("above", {0.0f, 4.0f, 1.0f}, {0.0f, 0.0f, 0.0f}, 60.0f);
  w.sun({0.0f, -1.0f, 0.0f}, 10.0f);
  w.sky({1.0f, 1.0f, 1.0f});
  w.write(dir);
}

// The texture-sampling probes share one 2x2 image, a texel per colour: top row (v < 0.5)
// red, green; bottom row blue, white (8-bit sRGB; 0 and 255 decode to 0 and 1 exactly). Each
// probe lays 1 m quads side by side on the ground (u along +X, v along -Z) under a camera
// above them; tests/gpu/test_gltf_probes.cpp reads which texel lands where.
int quadrantTexture(SceneWriter& w) {
  const std::vector<float> texels = {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
  return w.embeddedTexture("quadrants", encodeImage("png", 2, 2, 3, texels, 8), "image/png");
}

void probeView(SceneWriter& w, int quads) {
  w.camera("above", {0.0f, 0.9f * float(quads) + 1.0f, 0.6f}, {0.0f, 0.0f, 0.0f}, 50.0f);
  w.sun({0.0f, -1.0f, 0.0f}, 10.0f);
  w.sky({1.0f, 1.0f, 1.0f});
}

float probeX(int i, int quads) { return (float(i) - 0.5f * float(quads - 1)) * 1.1f; }

// KHR_texture_transform, nearest-filtered so texels stay whole: quads with no transform, an
// offset (0.5, 0), a rotation of pi/2 with offset (0, 1) (uv' = (v, 1 - u)), a scale (3, 1),
// and the identity with the extension's texCoord 1 picking a TEXCOORD_1 mirrored in u.
void textureTransformProbe(const std::filesystem::path& dir) {
  SceneWriter w("texture_transform_probe");
  const int texture = w.sampledTexture(quadrantTexture(w), TINYGLTF_TEXTURE_FILTER_NEAREST, TINYGLTF_TEXTURE_FILTER_NEAREST,
                                       TINYGLTF_TEXTURE_WRAP_REPEAT, TINYGLTF_TEXTURE_WRAP_REPEAT);
  struct Probe {
    const char* name;
    TextureUse use;
  };
  TextureUse offset{0, true, {0.5f, 0.0f}};
  TextureUse rotation{0, true, {0.0f, 1.0f}, 1.5707963f};
  TextureUse scale{0, true, {0.0f, 0.0f}, 0.0f, {3.0f, 1.0f}};
  TextureUse override{0, true, {0.0f, 0.0f}, 0.0f, {1.0f, 1.0f}, 1};
  const Probe probes[] = {{"identity", {}}, {"offset", offset}, {"rotation", rotation}, {"scale", scale}, {"texcoord_override", override}};
  const int n = int(std::size(probes));
  for (int i = 0; i < n; ++i) {
    MaterialSpec spec{probes[i].name, {1.0f, 1.0f, 1.0f}, 0.0f, 1.0f};
    spec.baseColorTextureIndex = texture;
    spec.baseColorUse = probes[i].use;
    Shape q = quad(1.0f, 1.0f);
    q.uvs1 = q.uvs;
    for (auto& uv : q.uvs1) uv.x = 1.0f - uv.x;
    w.node(probes[i].name, w.mesh(probes[i].name, q, w.material(spec)), {probeX(i, n), 0.0f, 0.0f});
  }
  probeView(w, n);
  w.write(dir);
}

// Sampler wrap modes and filters: quads whose UVs run from -1 to 2 across (v from 0 to 1)
// sample the quadrant image through REPEAT, CLAMP_TO_EDGE and MIRRORED_REPEAT (nearest), and a
// quad with UVs 0..1 magnifies it through LINEAR and one through NEAREST.
void samplerProbe(const std::filesystem::path& dir) {
  SceneWriter w("sampler_probe");
  const int image = quadrantTexture(w);
  struct Probe {
    const char* name;
    int filter, wrap;
    bool wide;
  };
  const Probe probes[] = {{"repeat", TINYGLTF_TEXTURE_FILTER_NEAREST, TINYGLTF_TEXTURE_WRAP_REPEAT, true},
                          {"clamp", TINYGLTF_TEXTURE_FILTER_NEAREST, TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE, true},
                          {"mirror", TINYGLTF_TEXTURE_FILTER_NEAREST, TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT, true},
                          {"linear", TINYGLTF_TEXTURE_FILTER_LINEAR, TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE, false},
                          {"nearest", TINYGLTF_TEXTURE_FILTER_NEAREST, TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE, false}};
  const int n = int(std::size(probes));
  for (int i = 0; i < n; ++i) {
    MaterialSpec spec{probes[i].name, {1.0f, 1.0f, 1.0f}, 0.0f, 1.0f};
    spec.baseColorTextureIndex = w.sampledTexture(image, probes[i].filter, probes[i].filter, probes[i].wrap, probes[i].wrap);
    Shape q = quad(1.0f, 1.0f);
    if (probes[i].wide)
      for (auto& uv : q.uvs) uv.x = uv.x * 3.0f - 1.0f;
    w.node(probes[i].name, w.mesh(probes[i].name, q, w.material(spec)), {probeX(i, n), 0.0f, 0.0f});
  }
  probeView(w, n);
  w.write(dir);
}

// A texture's texCoord index: the quad's TEXCOORD_0 is one point (the red texel's centre)
// and its TEXCOORD_1 the usual 0..1; the base-colour texture reads set 1, so all four texels
// show (set 0 would paint the quad red).
void texcoord1Probe(const std::filesystem::path& dir) {
  SceneWriter w("texcoord1_probe");
  const int texture = w.sampledTexture(quadrantTexture(w), TINYGLTF_TEXTURE_FILTER_NEAREST, TINYGLTF_TEXTURE_FILTER_NEAREST,
                                       TINYGLTF_TEXTURE_WRAP_REPEAT, TINYGLTF_TEXTURE_WRAP_REPEAT);
  MaterialSpec spec{"second_uv_set", {1.0f, 1.0f, 1.0f}, 0.0f, 1.0f};
  spec.baseColorTextureIndex = texture;
  spec.baseColorUse.texCoord = 1;
  Shape q = quad(1.0f, 1.0f);
  q.uvs1 = q.uvs;
  for (auto& uv : q.uvs) uv = {0.25f, 0.25f};
  w.node("second_uv_set", w.mesh("second_uv_set", q, w.material(spec)), {0.0f, 0.0f, 0.0f});
  probeView(w, 1);
  w.write(dir);
}

// COLOR_0 multiplied into the base colour (0.5 grey): white, black, red as float VEC3, green
// as normalized bytes, blue as normalized shorts, and a normalized-byte colour whose alpha 0
// cuts a MASK material out. Under the sky alone (no sun) a lone Lambertian-plus-specular quad
// reflects a ρ + s, linear in its albedo ρ, so (L_colour - L_black) / (L_white - L_black) is
// the colour itself, channel by channel (tests/gpu/test_gltf_probes.cpp).
void color0Probe(const std::filesystem::path& dir) {
  SceneWriter w("color0_probe");
  const int grey = w.material({"grey", {0.5f, 0.5f, 0.5f}, 0.0f, 1.0f});
  MaterialSpec maskSpec{"grey_mask", {0.5f, 0.5f, 0.5f}, 0.0f, 1.0f};
  maskSpec.alphaMode = "MASK";
  const int mask = w.material(maskSpec);
  struct Probe {
    const char* name;
    glm::vec4 colour;
    Shape::ColorType type;
    int material;
  };
  const Probe probes[] = {{"white", {1, 1, 1, 1}, Shape::ColorType::FloatVec3, grey},
                          {"black", {0, 0, 0, 1}, Shape::ColorType::FloatVec3, grey},
                          {"red", {1, 0, 0, 1}, Shape::ColorType::FloatVec3, grey},
                          {"green", {0, 1, 0, 1}, Shape::ColorType::UnormByteVec4, grey},
                          {"blue", {0, 0, 1, 1}, Shape::ColorType::UnormShortVec4, grey},
                          {"cut_out", {1, 1, 1, 0}, Shape::ColorType::UnormByteVec4, mask}};
  const int n = int(std::size(probes));
  for (int i = 0; i < n; ++i) {
    Shape q = quad(1.0f, 1.0f);
    q.colors.assign(q.positions.size(), probes[i].colour);
    q.colorType = probes[i].type;
    w.node(probes[i].name, w.mesh(probes[i].name, q, probes[i].material), {probeX(i, n), 0.0f, 0.0f});
  }
  w.camera("above", {0.0f, 0.9f * float(n) + 1.0f, 0.6f}, {0.0f, 0.0f, 0.0f}, 50.0f);
  w.sun({0.0f, -1.0f, 0.0f}, 0.0f);  // no sun: the importer's default one would shine otherwise
  w.sky({1.0f, 1.0f, 1.0f});
  w.write(dir);
}

// Alpha MASK everywhere: a 2 m red quad 1 m above a 0.8 grey floor whose base-colour texture's
// alpha is 0 on every texel (cutoff 0.5), under a sun straight overhead (E = 10) and a uniform
// sky (L = 1). Cut out in every stage, it leaves the floor below as lit as the open floor:
// radiance 0.8 / pi (E + pi L) = 3.346 in every path; a stage that sees it draws a shadow
// (0.8 L where only the sky reaches) or red light.
void cutout(const std::filesystem::path& dir) {
  SceneWriter w("cutout");
  std::vector<float> texels;
  for (int i = 0; i < 4 * 4; ++i) texels.insert(texels.end(), {1.0f, 0.0f, 0.0f, 0.0f});
  MaterialSpec card{"cut_out_card", {1.0f, 1.0f, 1.0f}, 0.0f, 1.0f};
  card.baseColorTextureIndex = w.embeddedTexture("transparent_red", encodeImage("png", 4, 4, 4, texels, 8), "image/png");
  card.alphaMode = "MASK";
  card.alphaCutoff = 0.5f;
  card.doubleSided = true;
  int grey = w.material({"floor_grey", {0.8f, 0.8f, 0.8f}, 0.0f, 1.0f});
  w.node("floor", w.mesh("floor", quad(20.0f, 20.0f), grey), {0.0f, 0.0f, 0.0f});
  w.node("card", w.mesh("card", quad(2.0f, 2.0f), w.material(card)), {0.0f, 1.0f, 0.0f});
  w.camera("above", {0.0f, 5.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, 50.0f);
  w.sun({0.0f, -1.0f, 0.0f}, 10.0f);
  w.sky({1.0f, 1.0f, 1.0f});
  w.write(dir);
}

// Alpha BLEND (stochastic transparency): a 2 m pane of smoked glass (base colour black, alpha
// 0.5 in its baseColorFactor, double-sided) 1 m above a 0.8 grey floor, under a sun of E = 10
// travelling (1, -1, 0) (45 degrees high) and no sky. The pane's shadow falls on x in [0, 2],
// z in [-1, 1]; it reflects nothing, so the floor there receives exactly half the sun: radiance
// 0.8 / pi * 10 cos 45 / 2 = 0.900 against the open floor's 1.801. Camera 0 looks down the
// line x = 1 from the +x side: its centre row is that line, its centre the shadow's, and no
// ray to that row crosses the pane. Camera 1 looks down through the pane; camera 2, from under
// its edge, at the floor under its centre, which with the sky alone (L = 1, the sun
// off) has the radiance 0.8 (1 - 0.5 F): F = 0.5541, the share of the sky's cosine-weighted
// light the pane hides there (a 2 m square 1 m up), so 0.5784 against the open floor's 0.8.
void translucentPane(const std::filesystem::path& dir) {
  SceneWriter w("translucent_pane");
  MaterialSpec glass{"smoked_glass", {0.0f, 0.0f, 0.0f}};
  glass.alpha = 0.5f;
  glass.alphaMode = "BLEND";
  glass.doubleSided = true;
  int grey = w.material({"floor_grey", {0.8f, 0.8f, 0.8f}, 0.0f, 1.0f});
  w.node("floor", w.mesh("floor", quad(20.0f, 20.0f), grey), {0.0f, 0.0f, 0.0f});
  w.node("pane", w.mesh("pane", quad(2.0f, 2.0f), w.material(glass)), {0.0f, 1.0f, 0.0f});
  w.camera("shadow", {5.0f, 4.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, 50.0f);
  w.camera("through_pane", {0.0f, 4.0f, 1.5f}, {0.0f, 0.0f, 0.0f}, 50.0f);
  w.camera("under_pane", {1.5f, 0.6f, 0.0f}, {0.0f, 0.0f, 0.0f}, 50.0f);
  w.sun({1.0f, -1.0f, 0.0f}, 10.0f);
  w.sky({0.0f, 0.0f, 0.0f});
  w.write(dir);
}

// A helmet-like asset as a PBR export carries it: one .glb with every texture inside (8-bit
// PNGs, 128 x 64 over the sphere's u and v): an sRGB base colour (olive paint with a white band
// and dark seams), metallic-roughness (the band bare metal, roughness 0.3; paint dielectric,
// 0.6), a normal map of raised panels with rounded seams and rivets and no TANGENT attribute
// (generated on import, MikkTSpace), an occlusion texture darkening the seams, and an emissive
// visor strip (strength 4). A 0.5 m shell (a sphere stretched 1.1 x tall) on a rim (a torus),
// standing on a grey ground, under a sun of E = 12 and a blue sky. Every path must render it
// as the reference does (a helmet-like asset).
void helmet(const std::filesystem::path& dir) {
  SceneWriter w("helmet");
  w.binary();
  const int width = 128, height = 64;
  const float pi = 3.14159265359f;
  // Panels: 8 across u, 4 down v; seams where a panel's coordinate is near an edge.
  const auto seam = [&](float u, float v) {
    const float pu = std::fmod(u * 8.0f, 1.0f), pv = std::fmod(v * 4.0f, 1.0f);
    const float d = std::min(std::min(pu, 1.0f - pu) * 2.0f, std::min(pv, 1.0f - pv));  // 0 at a seam
    return std::clamp(d / 0.08f, 0.0f, 1.0f);
  };
  const auto band = [](float v) { return v > 0.30f && v < 0.38f; };
  const auto visor = [](float u, float v) { return v > 0.42f && v < 0.5f && u > 0.72f && u < 0.94f; };  // facing the camera
  // The height field whose slopes the normal map holds: panels raised by their seams, a rivet
  // at each panel's corner.
  const auto heightAt = [&](float u, float v) {
    float h = 0.6f * seam(u, v);
    const float ru = std::fmod(u * 8.0f + 0.5f, 1.0f) - 0.5f, rv = std::fmod(v * 4.0f + 0.5f, 1.0f) - 0.5f;
    h += 0.5f * std::exp(-(ru * ru + rv * rv) / 0.004f);
    return h;
  };
  std::vector<float> base, metalRough, normal, occlusion, emissive;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float u = (float(x) + 0.5f) / float(width), v = (float(y) + 0.5f) / float(height);
      const float s = seam(u, v);
      glm::vec3 paint = band(v) ? glm::vec3(0.85f, 0.85f, 0.82f) : glm::vec3(0.33f, 0.36f, 0.18f);
      paint *= 0.35f + 0.65f * s;
      base.insert(base.end(), {paint.r, paint.g, paint.b});
      metalRough.insert(metalRough.end(), {0.0f, band(v) ? 0.3f : 0.6f, band(v) ? 1.0f : 0.0f});
      // Slopes per texel (the map's green is the image's top: +y towards decreasing v).
      const float du = 1.0f / float(width), dv = 1.0f / float(height), k = 0.04f;
      const float dhdu = (heightAt(u + du, v) - heightAt(u - du, v)) / (2.0f * du * 2.0f * pi * 0.5f) * k;
      const float dhdv = (heightAt(u, v + dv) - heightAt(u, v - dv)) / (2.0f * dv * pi * 0.55f) * k;
      const glm::vec3 n = glm::normalize(glm::vec3(-dhdu, dhdv, 1.0f));
      normal.insert(normal.end(), {n.x * 0.5f + 0.5f, n.y * 0.5f + 0.5f, n.z * 0.5f + 0.5f});
      const float ao = 0.45f + 0.55f * s;
      occlusion.insert(occlusion.end(), {ao, ao, ao});
      const float glow = visor(u, v) ? 1.0f : 0.0f;
      emissive.insert(emissive.end(), {glow * 1.0f, glow * 0.45f, glow * 0.1f});
    }
  MaterialSpec shell{"helmet_paint", {1.0f, 1.0f, 1.0f}, 1.0f, 1.0f, {1.0f, 1.0f, 1.0f}, 4.0f};
  shell.baseColorTextureIndex = w.embeddedTexture("helmet_base_color", encodeImage("png", width, height, 3, base, 8), "image/png");
  shell.metallicRoughnessTextureIndex =
      w.embeddedTexture("helmet_metallic_roughness", encodeImage("png", width, height, 3, metalRough, 8), "image/png");
  shell.normalTextureIndex = w.embeddedTexture("helmet_normal", encodeImage("png", width, height, 3, normal, 8), "image/png");
  shell.occlusionTextureIndex =
      w.embeddedTexture("helmet_occlusion", encodeImage("png", width, height, 3, occlusion, 8), "image/png");
  shell.emissiveTextureIndex = w.embeddedTexture("helmet_emissive", encodeImage("png", width, height, 3, emissive, 8), "image/png");
  const int paint = w.material(shell);
  const int rubber = w.material({"rim_rubber", {0.05f, 0.05f, 0.05f}, 0.0f, 0.7f});
  const int ground = w.material({"ground_grey", {0.5f, 0.5f, 0.5f}, 0.0f, 0.9f});
  w.node("ground", w.mesh("ground", quad(12.0f, 12.0f), ground), {0.0f, 0.0f, 0.0f});
  w.node("shell", w.mesh("shell", sphere(0.5f, 64, 32), paint), {0.0f, 0.62f, 0.0f}, {0.0f, 0.0f, 0.0f},
         {1.0f, 1.1f, 1.0f});
  w.node("rim", w.mesh("rim", torus(0.45f, 0.07f, 48, 12), rubber), {0.0f, 0.12f, 0.0f});
  w.camera("front", {1.1f, 1.0f, 1.9f}, {0.0f, 0.55f, 0.0f}, 45.0f);
  w.sun({-0.5f, -0.7f, -0.5f}, 12.0f);
  w.sky({0.45f, 0.6f, 0.9f});
  w.write(dir);
}

// An orthographic camera (glTF's xmag, ymag): three 0.5 m white cubes on a 0.8 grey ground at
// 1.06 m steps along the view, seen 45 degrees from above by camera 0, orthographic (xmag 2.4,
// ymag 1.8, near 0.1, far 30), and camera 1, a perspective one from the same place. Through the
// orthographic camera the three are the same size on screen (a perspective shrinks the far
// one); the view is lit by a sun of E = 10 travelling (0, -1, 0) and a sky of 1, so the open
// ground has 0.8 / pi (E + pi L) = 3.346 in every path, whichever way the rays leave the camera.
void orthographicProbe(const std::filesystem::path& dir) {
  SceneWriter w("orthographic_probe");
  int grey = w.material({"ground_grey", {0.8f, 0.8f, 0.8f}, 0.0f, 1.0f});
  int white = w.material({"white", {0.8f, 0.8f, 0.8f}, 0.0f, 1.0f});
  w.node("ground", w.mesh("ground", quad(30.0f, 30.0f), grey), {0.0f, 0.0f, 0.0f});
  const char* names[] = {"cube_far", "cube_middle", "cube_near"};
  for (int i = 0; i < 3; ++i)
    w.node(names[i], w.mesh(names[i], box({0.5f, 0.5f, 0.5f}), white), {1.2f * float(i - 1), 0.25f, 1.5f * float(i - 1)});
  w.orthographicCamera("orthographic", {0.0f, 6.0f, 6.0f}, {0.0f, 0.0f, 0.0f}, 2.4f, 1.8f, 0.1f, 30.0f);
  w.camera("perspective", {0.0f, 6.0f, 6.0f}, {0.0f, 0.0f, 0.0f}, 40.0f);
  w.sun({0.0f, -1.0f, 0.0f}, 10.0f);
  w.sky({1.0f, 1.0f, 1.0f});
  w.write(dir);
}

// Contact shadows (hybrid ray-traced shadows): a 1 m white cube standing on a 0.8 grey
// floor, under a sun of E = 10 travelling (0.6, -0.8, 0) (53 degrees high) and a sky of 1.
// With the real sun's 0.27 degree radius every penumbra is under 1.3 cm, so the floor's
// visibility is a closed form: 0 in the cube's shadow (x from its foot at -0.5 to +0.25,
// z within its sides), 1 elsewhere. A shadow map lifts the shadow off the contact and blurs
// its edges by its filter; a ray does not. Camera 0 looks down on the shadow.
void contactShadows(const std::filesystem::path& dir) {
  SceneWriter w("contact_shadows");
  int grey = w.material({"floor_grey", {0.8f, 0.8f, 0.8f}, 0.0f, 1.0f});
  int white = w.material({"white", {0.8f, 0.8f, 0.8f}, 0.0f, 0.8f});
  w.node("floor", w.mesh("floor", quad(12.0f, 12.0f), grey), {0.0f, 0.0f, 0.0f});
  w.node("cube", w.mesh("cube", box({1.0f, 1.0f, 1.0f}), white), {-1.0f, 0.5f, -1.0f});
  w.camera("above", {-0.6f, 4.0f, 0.4f}, {-0.6f, 0.0f, -1.0f}, 50.0f);
  w.sun({0.6f, -0.8f, 0.0f}, 10.0f);
  w.sky({1.0f, 1.0f, 1.0f});
  w.write(dir);
}

// The occlusion texture (glTF: it darkens indirect light only): three 1 m quads of the same
// grey dielectric side by side, under a sky of 1 and a sun of E = 10 straight overhead. The
// west one has an occlusion texture of 0.25 at strength 1, the middle one the same texture at
// strength 0.5, the east one none: their sky light stands 0.25 : 0.625 : 1 (the texel is
// 64/255, linear), their sunlight 1 : 1 : 1.
void occlusionProbe(const std::filesystem::path& dir) {
  SceneWriter w("occlusion_probe");
  const std::vector<float> quarter(4 * 4, 0.25f);
  const int occlusion = w.embeddedTexture("occlusion_quarter", encodeImage("png", 4, 4, 1, quarter, 8), "image/png");
  MaterialSpec full{"occluded", {0.8f, 0.8f, 0.8f}, 0.0f, 0.8f};
  full.occlusionTextureIndex = occlusion;
  MaterialSpec half = full;
  half.name = "half_occluded";
  half.occlusionStrength = 0.5f;
  const int plain = w.material({"plain", {0.8f, 0.8f, 0.8f}, 0.0f, 0.8f});
  w.node("occluded", w.mesh("occluded", quad(1.0f, 1.0f), w.material(full)), {-1.5f, 0.0f, 0.0f});
  w.node("half_occluded", w.mesh("half_occluded", quad(1.0f, 1.0f), w.material(half)), {0.0f, 0.0f, 0.0f});
  w.node("plain", w.mesh("plain", quad(1.0f, 1.0f), plain), {1.5f, 0.0f, 0.0f});
  w.camera("above", {0.0f, 4.0f, 0.01f}, {0.0f, 0.0f, 0.0f}, 50.0f);
  w.sun({0.0f, -1.0f, 0.0f}, 10.0f);
  w.sky({1.0f, 1.0f, 1.0f});
  w.write(dir);
}

// glTF doubleSided: five 0.8 m quads in a row 1.2 m up, seen against the sky, each named
// by what the camera must see of it. Single-sided ones facing the camera (one plain, one
// through a mirroring transform, whose winding glTF then reads clockwise) are drawn; single-
// sided ones facing away (plain and mirrored) are culled, so the sky shows where they stand;
// a double-sided one facing away shows its back. Every quad still casts its shadow on the
// ground behind it (the sun comes from behind the camera): culling is for the camera only.
void oneSidedProbe(const std::filesystem::path& dir) {
  SceneWriter w("one_sided_probe");
  MaterialSpec oneSided{"one_sided", {0.9f, 0.6f, 0.2f}, 0.0f, 0.8f};
  MaterialSpec twoSided{"double_sided", {0.2f, 0.7f, 0.3f}, 0.0f, 0.8f};
  twoSided.doubleSided = true;
  const int single = w.material(oneSided), both = w.material(twoSided);
  const int ground = w.material({"ground", {0.5f, 0.5f, 0.5f}, 0.0f, 0.9f});
  // 8 m deep: the camera's rays through the quads' row pass beyond it, into the sky.
  w.node("ground", w.mesh("ground", quad(12.0f, 8.0f), ground), {0.0f, 0.0f, 0.0f});
  const int singleQuad = w.mesh("single_quad", quad(0.8f, 0.8f), single);
  const int doubleQuad = w.mesh("double_quad", quad(0.8f, 0.8f), both);
  // quad() faces +Y: 90 degrees about X turn it towards the camera (+Z), -90 away from it.
  const glm::vec3 mirror(-1.0f, 1.0f, 1.0f);
  w.node("front_drawn", singleQuad, {-2.0f, 1.2f, 0.0f}, {90.0f, 0.0f, 0.0f});
  w.node("back_culled", singleQuad, {-1.0f, 1.2f, 0.0f}, {-90.0f, 0.0f, 0.0f});
  w.node("double_back_drawn", doubleQuad, {0.0f, 1.2f, 0.0f}, {-90.0f, 0.0f, 0.0f});
  w.node("mirrored_front_drawn", singleQuad, {1.0f, 1.2f, 0.0f}, {90.0f, 0.0f, 0.0f}, mirror);
  w.node("mirrored_back_culled", singleQuad, {2.0f, 1.2f, 0.0f}, {-90.0f, 0.0f, 0.0f}, mirror);
  w.camera("front", {0.0f, 2.0f, 4.5f}, {0.0f, 1.1f, 0.0f}, 50.0f);
  w.sun({0.0f, -1.0f, -1.5f}, 3.0f);
  w.sky({0.2f, 0.3f, 0.5f});
  w.write(dir);
}

// KHR_materials_ior, KHR_materials_specular and KHR_materials_unlit: a row of black, nearly
// smooth dielectric quads (roughness 0.1) under a uniform sky of radiance 1 and nothing else,
// seen from above. Head-on such a surface reflects Fresnel's ((n - 1) / (n + 1))^2 of the sky:
// ior 1 (nothing), 1.33, 1.5 (glTF's default), 2 and 2.42, then specularFactor 0 (nothing) and
// an unlit quad of base colour 0.25, which shows 0.25 whatever the light.
void iorProbe(const std::filesystem::path& dir) {
  SceneWriter w("ior_probe");
  struct Probe {
    const char* name;
    float ior, specular;
    bool unlit;
  };
  const Probe probes[] = {{"ior_1", 1.0f, 1.0f, false},    {"ior_1_33", 1.33f, 1.0f, false}, {"ior_1_5", 1.5f, 1.0f, false},
                          {"ior_2", 2.0f, 1.0f, false},    {"ior_2_42", 2.42f, 1.0f, false}, {"specular_0", 1.5f, 0.0f, false},
                          {"unlit_quarter", 1.5f, 1.0f, true}};
  const int n = int(std::size(probes));
  for (int i = 0; i < n; ++i) {
    MaterialSpec spec{probes[i].name, probes[i].unlit ? glm::vec3(0.25f) : glm::vec3(0.0f), 0.0f, 0.1f};
    if (probes[i].ior != 1.5f) spec.ior = probes[i].ior;
    if (probes[i].specular != 1.0f) spec.specularFactor = probes[i].specular;
    spec.unlit = probes[i].unlit;
    w.node(probes[i].name, w.mesh(probes[i].name, quad(1.0f, 1.0f), w.material(spec)), {probeX(i, n), 0.0f, 0.0f});
  }
  w.camera("above", {0.0f, 6.0f, 0.01f}, {0.0f, 0.0f, 0.0f}, 70.0f);
  w.sky({1.0f, 1.0f, 1.0f});
  w.write(dir);
}

// KHR_materials_transmission: a white room (base colour 0.8), 4 x 3 x 5 m inside 0.25 m walls,
// lit only by the sun (E = 20, travelling along (0, -0.6, -1): 31 degrees high, from the south)
// through a window of amber glass in its south wall: a 1.6 x 1.4 m opening (x -0.8..0.8, y
// 0.8..2.2) holding a smooth, thin, double-sided pane (base colour (0.9, 0.55, 0.25),
// transmission 1, ior 1.5: glTF's default) in the wall's middle plane. The sky is black, so
// the floor's direct light is the sun through the pane alone: a patch x -0.8..0.8, z -1.33..-3.42
// (the sill and the wall's depth bound it), where a floor of albedo rho shows
//   L = rho / pi x E cos(theta_floor) x baseColor (1 - F(theta_pane)),
// F the dielectric's Fresnel at the pane (the sun meets floor and pane at the same angle's
// complements: cos theta_floor = 0.514, cos theta_pane = 0.857). Camera `floor_patch` looks
// down at the patch's middle from 1.5 m above it and sees only the patch (30 degrees);
// `towards_window` shows the room and the pane.
void glassWindow(const std::filesystem::path& dir) {
  SceneWriter w("glass_window");
  const int white = w.material({"plaster_white", {0.8f, 0.8f, 0.8f}, 0.0f, 1.0f});
  MaterialSpec glass{"amber_glass", {0.9f, 0.55f, 0.25f}, 0.0f, 0.0f};
  glass.transmission = 1.0f;
  glass.doubleSided = true;
  const int amber = w.material(glass);
  const float t = 0.25f, h = 3.0f, x = 2.0f, z = -5.0f;
  const float left = -0.8f, right = 0.8f, sill = 0.8f, top = 2.2f;
  slab(w, "floor", white, {-x - t, -t, z - t}, {x + t, 0.0f, t});
  slab(w, "ceiling", white, {-x - t, h, z - t}, {x + t, h + t, t});
  slab(w, "wall_west", white, {-x - t, -t, z - t}, {-x, h + t, t});
  slab(w, "wall_east", white, {x, -t, z - t}, {x + t, h + t, t});
  slab(w, "wall_north", white, {-x, -t, z - t}, {x, h + t, z});
  slab(w, "wall_south_west", white, {-x, -t, 0.0f}, {left, h + t, t});
  slab(w, "wall_south_east", white, {right, -t, 0.0f}, {x, h + t, t});
  slab(w, "wall_under_window", white, {left, -t, 0.0f}, {right, sill, t});
  slab(w, "wall_over_window", white, {left, top, 0.0f}, {right, h + t, t});
  // The pane: a quad in XZ facing +Y turned to face +Z (south, towards the sun).
  w.node("pane", w.mesh("pane", quad(right - left, top - sill), amber), {0.0f, 0.5f * (sill + top), 0.5f * t},
         {90.0f, 0.0f, 0.0f});
  w.camera("floor_patch", {0.0f, 1.5f, -2.375f}, {0.0f, 0.0f, -2.4f}, 30.0f);
  w.camera("towards_window", {1.2f, 1.5f, -4.5f}, {-0.3f, 1.1f, 0.0f}, 65.0f);
  w.sun({0.0f, -0.6f, -1.0f}, 20.0f);
  w.sky({0.0f, 0.0f, 0.0f});
  w.write(dir);
}

// The white furnace with transmission: a white floor (base colour 1) under a uniform sky of 1,
// and above it a white thin pane (transmission 1, roughness 0.3) and a white glass box that
// bounds a clear volume (KHR_materials_volume). Everything reflects or passes on all the light
// it receives, so every pixel shows the sky's radiance, 1, under and through the glass as beside
// it.
void glassFurnace(const std::filesystem::path& dir) {
  SceneWriter w("glass_furnace");
  MaterialSpec floorSpec{"white", {1.0f, 1.0f, 1.0f}, 0.0f, 0.5f};
  floorSpec.doubleSided = true;
  const int white = w.material(floorSpec);
  MaterialSpec pane{"white_pane", {1.0f, 1.0f, 1.0f}, 0.0f, 0.3f};
  pane.transmission = 1.0f;
  pane.doubleSided = true;
  MaterialSpec block{"white_glass_block", {1.0f, 1.0f, 1.0f}, 0.0f, 0.0f};
  block.transmission = 1.0f;
  block.thickness = 0.5f;
  block.doubleSided = true;
  w.node("floor", w.mesh("floor", quad(40.0f, 40.0f), white), {0.0f, 0.0f, 0.0f});
  w.node("pane", w.mesh("pane", quad(1.5f, 1.5f), w.material(pane)), {-0.9f, 0.8f, 0.0f}, {20.0f, 0.0f, 0.0f});
  w.node("block", w.mesh("block", box({0.8f, 0.8f, 0.8f}), w.material(block)), {0.9f, 0.6f, 0.0f}, {0.0f, 30.0f, 0.0f});
  w.camera("above", {0.0f, 3.0f, 2.5f}, {0.0f, 0.3f, 0.0f}, 60.0f);
  w.sky({1.0f, 1.0f, 1.0f});
  w.write(dir);
}

// KHR_materials_volume: a glass block 1.2 x 1.2 x 0.5 m (smooth, clear surface of ior 1.5,
// transmission 1) bounding a volume that leaves attenuationColor (0.5, 0.7, 0.9) of the light
// after attenuationDistance 0.5 m, held in front of an unlit white wall (it shows 1 whatever
// the light) in the dark. Seen head-on through the block's 0.5 m, the wall shows
//   L = (1 - F)^2 attenuationColor^(0.5 / 0.5),   F = ((n - 1) / (n + 1))^2 = 0.04,
// (0.461, 0.645, 0.829) by Beer-Lambert and Fresnel at the two faces; beside the block, 1.
void glassVolume(const std::filesystem::path& dir) {
  SceneWriter w("glass_volume");
  MaterialSpec wallSpec{"unlit_white", {1.0f, 1.0f, 1.0f}, 0.0f, 1.0f};
  wallSpec.unlit = true;
  MaterialSpec glass{"tinted_glass_block", {1.0f, 1.0f, 1.0f}, 0.0f, 0.0f};
  glass.transmission = 1.0f;
  glass.thickness = 0.5f;
  glass.attenuationColor = {0.5f, 0.7f, 0.9f};
  glass.attenuationDistance = 0.5f;
  glass.doubleSided = true;
  // The wall: a quad in XZ facing +Y turned to face +Z, towards the camera.
  w.node("wall", w.mesh("wall", quad(6.0f, 4.0f), w.material(wallSpec)), {0.0f, 1.0f, -1.0f}, {90.0f, 0.0f, 0.0f});
  w.node("block", w.mesh("block", box({1.2f, 1.2f, 0.5f}), w.material(glass)), {0.0f, 1.0f, 0.0f});
  w.camera("head_on", {0.0f, 1.0f, 6.0f}, {0.0f, 1.0f, 0.0f}, 20.0f);
  w.sky({0.0f, 0.0f, 0.0f});
  w.write(dir);
}

// KHR_materials_clearcoat: two black, smooth dielectric quads (roughness 0.05) under a uniform
// sky of 1, seen from above: bare, head-on it reflects Fresnel's 0.04 of the sky; under a full,
// smooth clear coat (ior 1.5) the light meets two such interfaces, 1 - (1 - 0.04)^2 = 0.0784.
void clearcoatProbe(const std::filesystem::path& dir) {
  SceneWriter w("clearcoat_probe");
  MaterialSpec bare{"black_bare", {0.0f, 0.0f, 0.0f}, 0.0f, 0.05f};
  MaterialSpec coated{"black_coated", {0.0f, 0.0f, 0.0f}, 0.0f, 0.05f};
  coated.clearcoat = 1.0f;
  coated.clearcoatRoughness = 0.05f;
  w.node("black_bare", w.mesh("black_bare", quad(1.0f, 1.0f), w.material(bare)), {-0.6f, 0.0f, 0.0f});
  w.node("black_coated", w.mesh("black_coated", quad(1.0f, 1.0f), w.material(coated)), {0.6f, 0.0f, 0.0f});
  w.camera("above", {0.0f, 4.0f, 0.01f}, {0.0f, 0.0f, 0.0f}, 40.0f);
  w.sky({1.0f, 1.0f, 1.0f});
  w.write(dir);
}

// Scale: `instances` boxes on a 2 km square of ground, each one of `keys` distinct mesh and
// material combinations (albedo keys): 40 box shapes x as many materials as the keys need.
// The positions are a jittered grid, the shapes and materials and yaw a fixed hash of the
// index (the file is the same on every run). The camera `street` stands at eye height in the
// middle looking along the ground; `overview` looks down on all of it.
void sprawl(const std::filesystem::path& dir, uint32_t instances, uint32_t keys) {
  SceneWriter w("sprawl");
  const float side = 2000.0f;
  w.node("ground", w.mesh("ground", quad(side, side, 200.0f), w.material({"asphalt", {0.18f, 0.18f, 0.19f}, 0.0f, 0.9f})),
         {0.0f, 0.0f, 0.0f});
  const uint32_t shapes = std::min(keys, 40u), materials = (keys + shapes - 1) / shapes;
  auto hash = [](uint32_t x) {  // a 32-bit integer mix (fixed: the file must not change between runs)
    x ^= x >> 16, x *= 0x7feb352du, x ^= x >> 15, x *= 0x846ca68bu, x ^= x >> 16;
    return x;
  };
  std::vector<int> material(materials);
  for (uint32_t m = 0; m < materials; ++m) {
    const uint32_t h = hash(m + 7u);
    const glm::vec3 colour(0.15f + 0.7f * float(h & 255u) / 255.0f, 0.15f + 0.7f * float((h >> 8) & 255u) / 255.0f,
                           0.15f + 0.7f * float((h >> 16) & 255u) / 255.0f);
    char name[32];
    std::snprintf(name, sizeof name, "paint_%u", m);
    material[m] = w.material({name, colour, (h >> 24) % 4 == 0 ? 1.0f : 0.0f, 0.6f});
  }
  std::vector<int> mesh(keys);
  std::vector<float> height(keys);
  for (uint32_t k = 0; k < keys; ++k) {
    const uint32_t shape = k % shapes;
    const glm::vec3 size(1.0f + 0.1f * float(shape % 8), 0.8f + 0.35f * float(shape / 8), 1.0f + 0.15f * float(shape % 5));
    height[k] = size.y;
    char name[32];
    std::snprintf(name, sizeof name, "block_%u", k);
    mesh[k] = w.mesh(name, box(size), material[k / shapes]);
  }
  // One more column than a square of `instances` needs: the cells skipped for the street fit.
  const uint32_t columns = uint32_t(std::ceil(std::sqrt(double(instances)))) + 1;
  const float pitch = side / float(columns);
  for (uint32_t cell = 0, placed = 0; placed < instances; ++cell) {
    const float z = -0.5f * side + (float(cell / columns) + 0.5f) * pitch;
    if (std::abs(z) < 0.5f * pitch) continue;  // the street: a clear lane along x where the camera stands
    const uint32_t h = hash(cell), k = hash(cell ^ 0x9e3779b9u) % keys;
    const float jx = (float(h & 1023u) / 1023.0f - 0.5f) * 0.4f * pitch;
    const float jz = (float((h >> 10) & 1023u) / 1023.0f - 0.5f) * 0.4f * pitch;
    const glm::vec3 at(-0.5f * side + (float(cell % columns) + 0.5f) * pitch + jx, 0.5f * height[k], z + jz);
    char name[32];
    std::snprintf(name, sizeof name, "b%u", placed++);
    w.node(name, mesh[k], at, {0.0f, float((h >> 20) % 360u), 0.0f});
  }
  w.camera("street", {-600.0f, 1.7f, 0.0f}, {0.0f, 1.7f, 0.0f}, 60.0f);
  w.camera("overview", {-1300.0f, 900.0f, -1300.0f}, {0.0f, 0.0f, 0.0f}, 60.0f);
  w.sun({0.3f, -0.7f, 0.4f}, 20.0f);
  w.sky({0.6f, 0.75f, 1.0f});
  w.write(dir);
}

}  // namespace
}  // namespace tl::content

// tl_content_gen --corpus DIR SEED [FIRST=0] [COUNT=64]: the randomized interiors (corpus.h)
// and DIR/corpus.json listing what was drawn for each.
int corpusMain(int argc, char** argv) {
  try {
    if (argc < 4 || argc > 6) throw std::invalid_argument("expected DIR SEED [FIRST] [COUNT]");
    auto number = [](const char* text, const char* what) {
      size_t used = 0;
      const unsigned long long v = std::stoull(text, &used);
      if (used != std::strlen(text)) throw std::invalid_argument(std::string(what) + " is not a whole number");
      return v;
    };
    const uint64_t seed = number(argv[3], "SEED");
    const unsigned long long first = argc > 4 ? number(argv[4], "FIRST") : 0ull;
    const unsigned long long count = argc > 5 ? number(argv[5], "COUNT") : 64ull;
    if (count == 0 || count > 100000 || first > 1000000) throw std::invalid_argument("COUNT 1..100000, FIRST <= 1000000");
    const std::filesystem::path dir = argv[2];
    const auto scenes = tl::content::writeCorpus(dir, seed, uint32_t(first), uint32_t(count));
    std::string list = "{\n  \"seed\": " + std::to_string(seed) + ",\n  \"scenes\": [\n";
    for (size_t i = 0; i < scenes.size(); ++i) {
      const auto& c = scenes[i];
      char line[512];
      std::snprintf(line, sizeof line,
                    "    {\"name\": \"%s\", \"size_m\": %.4g, \"shape\": \"%s\", \"openings\": \"%s\", \"lights\": \"%s\", "
                    "\"albedo\": \"%s\", \"walls\": \"%s\", \"triangles\": %u, \"sealed_room\": %s}%s\n",
                    c.name.c_str(), double(c.size), c.shape.c_str(), c.openings.c_str(), c.lights.c_str(), c.albedo.c_str(),
                    c.walls.c_str(), c.triangles, c.sealedRoom ? "true" : "false", i + 1 < scenes.size() ? "," : "");
      list += line;
    }
    list += "  ]\n}\n";
    std::ofstream out(dir / "corpus.json", std::ios::binary | std::ios::trunc);
    out << list;
    out.close();
    if (!out) throw std::runtime_error("cannot write " + (dir / "corpus.json").string());
    std::printf("wrote %zu interiors of corpus %llu to %s\n", scenes.size(), (unsigned long long)seed, argv[2]);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tl_content_gen --corpus DIR SEED [FIRST] [COUNT]: %s\n", e.what());
    return 2;
  }
}

int main(int argc, char** argv) {
  if (argc >= 2 && std::string(argv[1]) == "--corpus") return corpusMain(argc, argv);
  if (argc >= 3 && std::string(argv[1]) == "--sprawl") {
    try {
      const uint32_t instances = argc > 3 ? uint32_t(std::stoul(argv[3])) : 100000u;
      const uint32_t keys = argc > 4 ? uint32_t(std::stoul(argv[4])) : 1000u;
      if (instances == 0 || keys == 0 || instances > 10000000u) throw std::invalid_argument("counts");
      std::filesystem::create_directories(argv[2]);
      tl::content::sprawl(argv[2], instances, keys);
      std::printf("wrote %s/sprawl.gltf\n", argv[2]);
      return 0;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "tl_content_gen: --sprawl DIR [instances >= 1] [keys >= 1]: %s\n", e.what());
      return 2;
    }
  }
  if (argc != 2) {
    std::fprintf(stderr, "usage: tl_content_gen <content-dir> | tl_content_gen --sprawl <dir> [instances] [keys]\n");
    return 2;
  }
  try {
    std::filesystem::path dir = argv[1];
    tl::content::atrium(dir);
    tl::content::cornell(dir);
    tl::content::furnace(dir);
    tl::content::metalCornell(dir, "metal_cornell", 0.05f);
    tl::content::metalCornell(dir, "metal_cornell_rough", 0.25f);
    tl::content::polishedMetals(dir);
    tl::content::metalFurnace(dir);
    tl::content::mirrorFloor(dir);
    tl::content::wetStreet(dir);
    tl::content::plane(dir);
    tl::content::grove(dir);
    tl::content::banners(dir);
    tl::content::sparks(dir);
    tl::content::whiteFurnace(dir);
    tl::content::corridor(dir);
    tl::content::closedBox(dir);
    tl::content::doorwayRoom(dir);
    tl::content::slitCorridor(dir);
    tl::content::twinRooms(dir);
    tl::content::movingDoor(dir);
    tl::content::walker(dir);
    tl::content::lamps(dir);
    tl::content::lampGrid(dir);
    tl::content::areaRoom(dir);
    tl::content::lampsWithPanel(dir);
    tl::content::courtyard(dir);
    tl::content::embeddedTextures(dir);
    tl::content::normalProbe(dir);
    tl::content::cutout(dir);
    tl::content::translucentPane(dir);
    tl::content::helmet(dir);
    tl::content::orthographicProbe(dir);
    tl::content::textureTransformProbe(dir);
    tl::content::samplerProbe(dir);
    tl::content::texcoord1Probe(dir);
    tl::content::color0Probe(dir);
    tl::content::contactShadows(dir);
    tl::content::occlusionProbe(dir);
    tl::content::oneSidedProbe(dir);
    tl::content::iorProbe(dir);
    tl::content::glassWindow(dir);
    tl::content::glassFurnace(dir);
    tl::content::glassVolume(dir);
    tl::content::clearcoatProbe(dir);
    tl::content::writeHardScenes(dir / "hard");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tl_content_gen: %s\n", e.what());
    return 1;
  }
  return 0;
}
