// The hard-case corpus, content/hard/: small scenes that each push one number to
// where renderers break -- far from the origin, a millimetre next to a kilometre, paper-thin
// walls, degenerate triangles, emitters of 1e5 next to diffuse walls, black and mirror
// materials, a grazing sun. `twinlight doctor` runs every lighting path on each and CI
// expects no NaN, no Inf, no negative radiance and no validation message (content/README.md).
#include "hard_scenes.h"

#include <cmath>

namespace tl::content {
namespace {

// A 4 x 3 x 4 m room open at the front, around `origin`, with a sun through the opening.
void room(SceneWriter& w, glm::vec3 origin, int wallMaterial) {
  const Shape floor = quad(4.0f, 4.0f);
  w.node("floor", w.mesh("floor", floor, wallMaterial), origin);
  w.node("back", w.mesh("back", box({4.0f, 3.0f, 0.1f}), wallMaterial), origin + glm::vec3(0.0f, 1.5f, -2.0f));
  w.node("left", w.mesh("left", box({0.1f, 3.0f, 4.0f}), wallMaterial), origin + glm::vec3(-2.0f, 1.5f, 0.0f));
}

// 1e7 m from the origin on two axes: camera-relative rendering must keep it exact.
void farFromOrigin(const std::filesystem::path& dir) {
  SceneWriter w("far_origin");
  const glm::vec3 o(1.0e7f, 0.0f, -1.0e7f);
  int white = w.material({"white", {0.8f, 0.8f, 0.8f}});
  room(w, o, white);
  w.node("box", w.mesh("box", box({0.6f, 0.6f, 0.6f}), white), o + glm::vec3(0.3f, 0.3f, -0.5f), {0.0f, 25.0f, 0.0f});
  w.camera("front", o + glm::vec3(0.0f, 1.2f, 3.5f), o + glm::vec3(0.0f, 0.8f, 0.0f), 50.0f);
  w.sun(glm::normalize(glm::vec3(-0.3f, -1.0f, -0.6f)), 20.0f);
  w.sky({1.0f, 1.0f, 1.0f});
  w.write(dir);
}

// A 1 mm cube on a 2 km ground, seen from 5 cm: depth range and shadow fitting.
void tinyNextToHuge(const std::filesystem::path& dir) {
  SceneWriter w("tiny_huge");
  int grey = w.material({"grey", {0.5f, 0.5f, 0.5f}});
  int red = w.material({"red", {0.8f, 0.1f, 0.1f}});
  w.node("ground", w.mesh("ground", quad(2000.0f, 2000.0f, 100.0f), grey), {0.0f, 0.0f, 0.0f});
  w.node("speck", w.mesh("speck", box({0.001f, 0.001f, 0.001f}), red), {0.0f, 0.0005f, 0.0f}, {0.0f, 30.0f, 0.0f});
  w.camera("close", {0.0f, 0.02f, 0.05f}, {0.0f, 0.0f, 0.0f}, 40.0f);
  w.sun(glm::normalize(glm::vec3(-0.5f, -1.0f, -0.2f)), 20.0f);
  w.sky({1.0f, 1.0f, 1.0f});
  w.write(dir);
}

// Sheets 0.1 mm thick between the sun and a floor, seen at a grazing angle.
void thinGeometry(const std::filesystem::path& dir) {
  SceneWriter w("thin");
  int white = w.material({"white", {0.8f, 0.8f, 0.8f}});
  int paper = w.material({"paper", {0.9f, 0.85f, 0.7f}});
  w.node("floor", w.mesh("floor", quad(10.0f, 10.0f), white), {0.0f, 0.0f, 0.0f});
  const int sheet = w.mesh("sheet", box({2.0f, 0.0001f, 2.0f}), paper);
  for (int i = 0; i < 3; ++i)
    w.node("sheet_" + std::to_string(i), sheet, {-2.5f + 2.5f * float(i), 0.6f + 0.3f * float(i), 0.0f},
           {0.0f, 0.0f, 10.0f * float(i)});
  w.node("fin", w.mesh("fin", box({0.0001f, 1.0f, 3.0f}), paper), {0.0f, 0.5f, 2.0f});
  w.camera("grazing", {6.0f, 0.15f, 6.0f}, {0.0f, 0.3f, 0.0f}, 45.0f);
  w.sun(glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f)), 20.0f);
  w.sky({1.0f, 1.0f, 1.0f});
  w.write(dir);
}

// Zero-area triangles (repeated and collinear vertices) inside an ordinary mesh.
void degenerateTriangles(const std::filesystem::path& dir) {
  SceneWriter w("degenerate");
  int white = w.material({"white", {0.8f, 0.8f, 0.8f}});
  Shape s = box({1.0f, 1.0f, 1.0f});
  const uint32_t base = uint32_t(s.positions.size());
  for (int i = 0; i < 3; ++i) {
    s.positions.push_back({0.5f, 0.5f + 0.25f * float(i), 0.5f});  // collinear
    s.normals.push_back({0.0f, 0.0f, 0.0f});                         // and no normal
    s.uvs.push_back({0.0f, 0.0f});
  }
  for (uint32_t i : {0u, 1u, 2u, 0u, 0u, 0u, 1u, 1u, 2u}) s.indices.push_back(base + i);
  w.node("cube", w.mesh("cube", s, white), {0.0f, 0.5f, 0.0f}, {0.0f, 20.0f, 0.0f});
  w.node("ground", w.mesh("ground", quad(8.0f, 8.0f), white), {0.0f, 0.0f, 0.0f});
  w.camera("front", {2.0f, 1.5f, 2.5f}, {0.0f, 0.5f, 0.0f}, 50.0f);
  w.sun(glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f)), 20.0f);
  w.sky({1.0f, 1.0f, 1.0f});
  w.write(dir);
}

// Two walls emitting 1e5 (the luminance of a bright lamp's filament) facing diffuse ones:
// the SH of every path's irradiance lies beyond the half-float range.
void strongEmitters(const std::filesystem::path& dir) {
  SceneWriter w("emitters");
  int white = w.material({"white", {0.8f, 0.8f, 0.8f}});
  int hot = w.material({"hot", {0.0f, 0.0f, 0.0f}, 0.0f, 1.0f, {1.0f, 0.6f, 0.3f}, 1.0e5f});
  int green = w.material({"green", {0.1f, 0.9f, 0.1f}, 0.0f, 1.0f, {0.1f, 1.0f, 0.1f}, 1.0e4f});
  room(w, {0.0f, 0.0f, 0.0f}, white);
  w.node("hot_panel", w.mesh("hot_panel", box({0.1f, 1.0f, 1.5f}), hot), {1.9f, 1.0f, -0.5f});
  w.node("green_strip", w.mesh("green_strip", box({2.0f, 0.05f, 0.05f}), green), {0.0f, 2.5f, -1.9f});
  w.camera("front", {0.0f, 1.4f, 3.5f}, {0.0f, 1.0f, 0.0f}, 55.0f);
  w.sky({0.0f, 0.0f, 0.0f});
  w.write(dir);
}

// Black (albedo 0), white (1) and mirror (metal, roughness 0) surfaces side by side.
void blackAndMetal(const std::filesystem::path& dir) {
  SceneWriter w("black_metal");
  int black = w.material({"black", {0.0f, 0.0f, 0.0f}});
  int white = w.material({"white", {1.0f, 1.0f, 1.0f}});
  int mirror = w.material({"mirror", {1.0f, 1.0f, 1.0f}, 1.0f, 0.0f});
  int gold = w.material({"rough_gold", {1.0f, 0.77f, 0.34f}, 1.0f, 1.0f});
  w.node("ground", w.mesh("ground", quad(8.0f, 8.0f), black), {0.0f, 0.0f, 0.0f});
  w.node("white_sphere", w.mesh("white_sphere", sphere(0.5f, 32, 16), white), {-1.2f, 0.5f, 0.0f});
  w.node("mirror_sphere", w.mesh("mirror_sphere", sphere(0.5f, 32, 16), mirror), {0.0f, 0.5f, 0.0f});
  w.node("gold_box", w.mesh("gold_box", box({0.8f, 0.8f, 0.8f}), gold), {1.2f, 0.4f, 0.0f}, {0.0f, 30.0f, 0.0f});
  w.node("mirror_wall", w.mesh("mirror_wall", box({6.0f, 2.0f, 0.05f}), mirror), {0.0f, 1.0f, -1.5f});
  w.camera("front", {0.0f, 1.2f, 3.5f}, {0.0f, 0.5f, 0.0f}, 50.0f);
  w.sun(glm::normalize(glm::vec3(-0.5f, -1.0f, -0.4f)), 20.0f);
  w.sky({1.0f, 1.0f, 1.0f});
  w.write(dir);
}

// The sun a hundredth of a radian above the horizon over boxes on a plane: shadows a
// hundred times longer than the boxes, and surfaces lit at grazing incidence.
void grazingSun(const std::filesystem::path& dir) {
  SceneWriter w("grazing_sun");
  int white = w.material({"white", {0.8f, 0.8f, 0.8f}});
  w.node("ground", w.mesh("ground", quad(200.0f, 200.0f, 10.0f), white), {0.0f, 0.0f, 0.0f});
  const int crate = w.mesh("crate", box({1.0f, 1.0f, 1.0f}), white);
  for (int i = 0; i < 4; ++i)
    w.node("crate_" + std::to_string(i), crate, {-3.0f + 2.0f * float(i), 0.5f, -2.0f * float(i % 2)}, {0.0f, 15.0f * float(i), 0.0f});
  w.camera("low", {0.0f, 1.5f, 6.0f}, {0.0f, 0.5f, -2.0f}, 55.0f);
  w.sun(glm::normalize(glm::vec3(1.0f, -0.01f, 0.2f)), 50.0f);
  w.sky({0.5f, 0.6f, 0.8f});
  w.write(dir);
}

}  // namespace

void writeHardScenes(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  farFromOrigin(dir);
  tinyNextToHuge(dir);
  thinGeometry(dir);
  degenerateTriangles(dir);
  strongEmitters(dir);
  blackAndMetal(dir);
  grazingSun(dir);
}

}  // namespace tl::content
