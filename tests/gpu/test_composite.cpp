// The composite against closed forms computed on the CPU with the same shared shading
// code: a white-ish plane under a sun from straight above and a uniform sky, the sky
// itself, and a floor under a roof (in the sun's shadow).
#include "gpu_fixture.h"

#include "lighting/common/composite_pass.h"
#include "shared/color.h"
#include "shared/shading.h"

namespace tl::test {
namespace {

glm::vec3 pixel(const graph::Readback& rb, uint32_t x, uint32_t y) {
  auto t = rb.texels();
  size_t i = (size_t(y) * rb.extent.width + x) * rb.channels();
  return {t[i], t[i + 1], t[i + 2]};
}

// Radiance the composite must produce for an unshadowed, non-emissive surface.
glm::vec3 expectedRadiance(glm::vec3 baseColor, float roughness, float metallic, glm::vec3 n, glm::vec3 v,
                           glm::vec3 toSun, glm::vec3 sunE, glm::vec3 skyL, float visibility) {
  using namespace shared;
  // The G-buffer stores base colour as 8-bit sRGB: quantise the same way.
  glm::vec3 q = tlSrgbToLinear(glm::round(tlLinearToSrgb(baseColor) * 255.0f) / 255.0f);
  SurfaceParams s = tlSurface(q, roughness, metallic);
  glm::vec3 r = skyL * tlEnvironmentAlbedo(s, glm::dot(n, v));
  float nl = glm::dot(n, toSun);
  if (nl > 0) r += sunE * nl * visibility * tlBrdf(s, n, v, toSun);
  return r;
}

}  // namespace

TEST_F(GpuTest, PlaneUnderSunAndSkyMatchesTheClosedForm) {
  auto& s = session();
  s.loadScene(contentFile("plane.gltf"));
  s.setSize(64, 64);
  session::View v = s.view();
  v.position = {0.0, 3.0, 3.0};
  v.forward = glm::normalize(glm::dvec3(0.0, -3.0, -3.0));
  v.up = {0, 1, 0};
  v.yfovRadians = glm::radians(60.0f);
  s.setView(v);
  session::Lighting l = s.lighting();
  l.sunDirection = {0.0, -1.0, 0.0};
  l.sunIrradiance = glm::vec3(10.0f);
  l.skyRadiance = glm::vec3(1.0f);
  s.setLighting(l);
  s.renderFrames(1);
  const auto& hdr = s.buffer(lighting::kCompositeHdr);

  // Centre pixel: the ray through it hits the origin.
  const auto& m = s.scene().materials[s.scene().meshes[0].material];
  glm::vec3 expected = expectedRadiance(glm::vec3(m.baseColorFactor), m.roughness, m.metallic, {0, 1, 0},
                                        glm::normalize(glm::vec3(0, 3, 3)), {0, 1, 0}, glm::vec3(10.0f), glm::vec3(1.0f), 1.0f);
  glm::vec3 got = (pixel(hdr, 31, 31) + pixel(hdr, 32, 32) + pixel(hdr, 31, 32) + pixel(hdr, 32, 31)) * 0.25f;
  EXPECT_NEAR(got.x, expected.x, 0.02f * expected.x) << "expected " << expected.x;
  EXPECT_NEAR(got.y, expected.y, 0.02f * expected.y);

  // Looking up: every pixel sees the sky, and the sky is exactly L (half floats hold 1.0).
  v.forward = glm::normalize(glm::dvec3(0.0, 1.0, -0.3));
  s.setView(v);
  s.renderFrames(1);
  glm::vec3 sky = pixel(s.buffer(lighting::kCompositeHdr), 32, 32);
  EXPECT_EQ(sky, glm::vec3(1.0f));
}

TEST_F(GpuTest, FloorUnderARoofIsInTheSunsShadow) {
  auto& s = session();
  s.loadScene(contentFile("atrium.gltf"));
  s.setSize(64, 64);
  session::View v = s.view();
  v.position = {5.0, 1.7, -5.0};  // inside the interior room, looking down at its floor
  v.forward = glm::normalize(glm::dvec3(0.0, -1.7, -2.0));
  v.up = {0, 1, 0};
  v.yfovRadians = glm::radians(30.0f);
  s.setView(v);
  session::Lighting l = s.lighting();
  l.sunDirection = {0.0, -1.0, 0.0};  // straight down: the roof shades the whole floor
  s.setLighting(l);
  s.requestBuffer("gbuffer.instanceId");
  s.renderFrames(1);

  const auto& hdr = s.buffer(lighting::kCompositeHdr);
  const scene::Material* floor = nullptr;
  for (auto& m : s.scene().materials)
    if (m.name == "stone_floor") floor = &m;
  ASSERT_NE(floor, nullptr);
  glm::vec3 n(0, 1, 0);
  glm::vec3 view = glm::normalize(glm::vec3(0.0f, 1.7f, 2.0f));
  glm::vec3 shadowed = expectedRadiance(glm::vec3(floor->baseColorFactor), floor->roughness, floor->metallic, n, view, n,
                                        l.sunIrradiance, l.skyRadiance, 0.0f);
  glm::vec3 lit = expectedRadiance(glm::vec3(floor->baseColorFactor), floor->roughness, floor->metallic, n, view, n,
                                   l.sunIrradiance, l.skyRadiance, 1.0f);
  ASSERT_GT(lit.y, 3.0f * shadowed.y);  // the test can tell the two apart
  glm::vec3 got = pixel(hdr, 32, 32);
  EXPECT_NEAR(got.y, shadowed.y, 0.03f * shadowed.y) << "lit would be " << lit.y;
}

TEST_F(GpuTest, ExrAndPngAreWrittenAtomically) {
  auto& s = session();
  s.loadScene(contentFile("cornell.gltf"));
  s.setSize(32, 32);
  s.renderFrames(1);
  auto dir = std::filesystem::temp_directory_path() / "twinlight-gpu-images";
  std::filesystem::remove_all(dir);
  s.saveImage(dir / "c.exr");
  s.saveImage(dir / "c.png");
  EXPECT_TRUE(std::filesystem::exists(dir / "c.exr"));
  EXPECT_TRUE(std::filesystem::exists(dir / "c.png"));
  size_t files = 0;
  for (auto& e : std::filesystem::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 2u);  // no temporary left behind
  EXPECT_THROW(s.saveImage(dir / "c.tga"), session::SessionError);
  std::filesystem::remove_all(dir);
}

}  // namespace tl::test
