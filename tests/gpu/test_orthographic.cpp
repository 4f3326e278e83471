// Orthographic cameras (glTF's xmag/ymag; content/orthographic_probe.gltf): three equal cubes at
// different distances along the view are the same size on screen, exactly as wide as xmag
// says, in every path (the raster's projection and the reference's parallel rays from the near
// plane), and the open ground keeps its closed form 0.8 / pi (E + pi L) = 3.346 in every path
// (the view vector, the sky through a pixel, the histories' depth tests all follow the camera).
#include "gpu_fixture.h"

#include "../common/test_scenes.h"

#include <cstdio>
#include <map>

namespace tl::test {
namespace {

using OrthographicTest = RayTracingTest;

const char* kCubes[] = {"cube_far", "cube_middle", "cube_near"};

// Per cube: its pixels, its widest row, and its interior (pixels whose 3x3 neighbours are it).
struct CubeOnScreen {
  size_t pixels = 0;
  uint32_t widest = 0;
  std::vector<size_t> interior;
};

std::map<std::string, CubeOnScreen> cubesOnScreen(const scene::Scene& scene, const std::vector<float>& ids, uint32_t width,
                                                  uint32_t height) {
  std::map<std::string, CubeOnScreen> out;
  for (const char* name : kCubes) {
    const uint32_t id = instanceIdOf(scene, name);
    CubeOnScreen& c = out[name];
    const auto is = [&](uint32_t x, uint32_t y) { return uint32_t(ids[size_t(y) * width + x]) == id; };
    for (uint32_t y = 0; y < height; ++y) {
      uint32_t row = 0;
      for (uint32_t x = 0; x < width; ++x) {
        if (!is(x, y)) continue;
        ++c.pixels;
        ++row;
        bool inside = x > 0 && y > 0 && x + 1 < width && y + 1 < height;
        for (int dy = -1; inside && dy <= 1; ++dy)
          for (int dx = -1; inside && dx <= 1; ++dx) inside = is(x + dx, y + dy);
        if (inside) c.interior.push_back(size_t(y) * width + x);
      }
      c.widest = std::max(c.widest, row);
    }
  }
  return out;
}

TEST_F(OrthographicTest, EqualCubesAreEqualOnScreenAtEveryDistance) {
  auto& s = session();
  const uint32_t width = 320, height = 240;
  const auto render = [&](size_t camera) {
    s.loadScene(contentFile("orthographic_probe.gltf"));
    s.useSceneCamera(camera);
    s.setPath("direct");
    s.setSize(width, height);
    s.requestBuffer("gbuffer.instanceId");
    s.renderFrames(1);
    return cubesOnScreen(s.scene(), s.buffer("gbuffer.instanceId").texels(), width, height);
  };
  ASSERT_TRUE(s.scene().ignored.empty());
  const auto orthographic = render(0);
  // The image's half-width is ymag x aspect = 1.8 x 4/3 = 2.4 m = xmag: a 0.5 m face is 0.5 / 4.8 of the width.
  const double faceWidth = 0.5 / 4.8 * width;
  for (const char* name : kCubes) {
    const CubeOnScreen& c = orthographic.at(name);
    std::printf("[ ortho    ] %-11s %zu pixels, widest row %u (closed form %.1f)\n", name, c.pixels, c.widest, faceWidth);
    EXPECT_NEAR(double(c.pixels) / double(orthographic.at("cube_middle").pixels), 1.0, 0.03) << name;
    EXPECT_NEAR(double(c.widest), faceWidth, 1.0) << name;
  }
  // The perspective camera in the same place shrinks the far cube: the test can tell them apart.
  const auto perspective = render(1);
  const double shrink = double(perspective.at("cube_far").pixels) / double(perspective.at("cube_near").pixels);
  std::printf("[ ortho    ] perspective camera: far / near cube pixels %.3f\n", shrink);
  EXPECT_LT(shrink, 0.8);
}

TEST_F(OrthographicTest, EveryPathRendersThroughTheOrthographicCamera) {
  auto& s = session();
  const uint32_t width = 160, height = 120;
  const double closedForm = 0.8 / glm::pi<double>() * (10.0 + glm::pi<double>());  // 3.346
  std::map<std::string, std::map<std::string, double>> cubeMeans;  // path -> cube -> mean green of its interior
  std::map<std::string, CubeOnScreen> cubes;
  for (const char* path : {"direct", "legacy", "rt", "reference"}) {
    SCOPED_TRACE(path);
    s.loadScene(contentFile("orthographic_probe.gltf"));
    s.useSceneCamera(0);
    s.settings().materials = lighting::MaterialMode::Diffuse;  // Lambert 0.8: the closed form
    s.settings().referenceSamplesPerFrame = 8;
    const uint32_t frames = std::string(path) == "reference" ? 8 : std::string(path) == "direct" ? 1 : 16;
    renderFresh(s, path, width, height, frames, {"gbuffer.instanceId"});
    s.settings().materials = lighting::MaterialMode::Authored;
    const auto radiance = s.buffer(finalImageOf(path)).texels();
    if (cubes.empty()) cubes = cubesOnScreen(s.scene(), s.buffer("gbuffer.instanceId").texels(), width, height);
    // Open ground in the lower left corner, away from every cube.
    double ground = 0.0;
    for (uint32_t y = height - 20; y < height - 4; ++y)
      for (uint32_t x = 4; x < 20; ++x) ground += radiance[(size_t(y) * width + x) * 4 + 1];
    ground /= 256.0;
    std::printf("[ ortho    ] %-9s open ground %.4f (closed form %.4f)", path, ground, closedForm);
    EXPECT_NEAR(ground / closedForm, 1.0, 0.02);
    for (const auto& [name, c] : cubes) {
      ASSERT_GT(c.interior.size(), 20u) << name;
      double sum = 0.0;
      for (size_t p : c.interior) sum += radiance[4 * p + 1];
      cubeMeans[path][name] = sum / double(c.interior.size());
      std::printf("  %s %.4f", name.c_str(), cubeMeans[path][name]);
    }
    std::printf("\n");
  }
  // Each cube where the rasterized G-buffer has it (its sunlit top and its front face, lit by the
  // sky and the ground): the reference's parallel rays find the same surfaces there, and the
  // three equal cubes look alike; the rt path, which carries the ground's bounce, agrees with
  // the reference within 10% (direct and legacy miss part of that bounce: printed).
  for (const char* name : kCubes) {
    EXPECT_NEAR(cubeMeans["reference"][name] / cubeMeans["reference"]["cube_middle"], 1.0, 0.05) << name;
    EXPECT_NEAR(cubeMeans["rt"][name] / cubeMeans["reference"][name], 1.0, 0.10) << name;
  }
}

}  // namespace
}  // namespace tl::test
