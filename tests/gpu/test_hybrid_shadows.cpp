// Hybrid ray-traced shadows (GameWorks HRTS) on content/contact_shadows.gltf: a 1 m cube
// on a floor under the real sun, whose penumbrae (under 1.3 cm) are a fraction of a pixel
// here, so the floor's sun visibility is a closed form: 0 inside the cube's shadow, 1 outside.
// The hybrid pass's buffer must match it, including along the contact, where the shadow map
// lifts the shadow off the cube's foot and blurs its sides; a wide sun must hand the blend
// back to the map's soft penumbra.
#include "gpu_fixture.h"

#include "lighting/common/composite_pass.h"
#include "lighting/common/hybrid_shadow_pass.h"
#include "shared/common.h"
#include "shared/packing.h"
#include "session/view_math.h"

#include <algorithm>

namespace tl::test {
namespace {

constexpr uint32_t kSize = 128;
// The cube spans x, z in [-1.5, -0.5] and y in [0, 1]; the sun travels (0.6, -0.8, 0), so the
// shadow runs from the cube's foot at x = -0.5 to x = -0.5 + 1 * 0.6 / 0.8 = 0.25.
constexpr double kFootX = -0.5, kShadowEndX = 0.25, kSideZ0 = -1.5, kSideZ1 = -0.5;

// Straight down on the shadow from 3 m: every floor point with x > -0.5 is seen past the cube.
session::View viewFromAbove() {
  session::View v;
  v.position = {-0.125, 3.0, -1.0};
  v.forward = {0.0, -1.0, 0.0};
  v.up = {0.0, 0.0, -1.0};
  v.yfovRadians = 0.8f;
  return v;
}

// The floor point (y = 0) under the centre of pixel (i, j).
glm::dvec3 floorPoint(const session::View& view, uint32_t i, uint32_t j) {
  const glm::dmat4 inverse = glm::inverse(session::cameraMatrices(view, 1.0).viewProj);
  const glm::dvec2 ndc((i + 0.5) / kSize * 2.0 - 1.0, (j + 0.5) / kSize * 2.0 - 1.0);
  const glm::dvec4 nearH = inverse * glm::dvec4(ndc, 1.0, 1.0), midH = inverse * glm::dvec4(ndc, 0.5, 1.0);
  const glm::dvec3 a = glm::dvec3(nearH) / nearH.w + view.position, b = glm::dvec3(midH) / midH.w + view.position;
  return a + (b - a) * (a.y / (a.y - b.y));
}

struct Floor {
  std::vector<double> exact;  // 0 or 1 where the closed form is unambiguous at this pixel, else -1
  double footprint = 0.0;     // one pixel on the floor, metres
};

// The closed form per pixel, leaving out pixels within a pixel and a half (plus the real sun's
// widest penumbra) of the shadow's free edges, and those that do not see the floor.
Floor closedForm(const session::View& view, const std::vector<float>& normals) {
  Floor f;
  f.footprint = glm::length(floorPoint(view, kSize / 2 + 1, kSize / 2) - floorPoint(view, kSize / 2, kSize / 2));
  const double margin = 1.5 * f.footprint + 0.013;
  f.exact.assign(kSize * kSize, -1.0);
  for (uint32_t j = 0; j < kSize; ++j)
    for (uint32_t i = 0; i < kSize; ++i) {
      const size_t k = j * kSize + i;
      const glm::vec3 n = shared::tlOctDecode(glm::vec2(normals[2 * k], normals[2 * k + 1]));
      const glm::dvec3 p = floorPoint(view, i, j);
      // The cube's faces, and its top (whose ray meets the floor behind the foot). Right at the
      // foot the closed form holds: the shadow starts at the contact line.
      if (n.y < 0.95f || p.x < kFootX + 1e-3) continue;
      const double toEdge = std::min({std::abs(p.x - kShadowEndX), std::abs(p.z - kSideZ0), std::abs(p.z - kSideZ1)});
      if (toEdge < margin) continue;
      const bool shadowed = p.x < kShadowEndX && p.z > kSideZ0 && p.z < kSideZ1;
      f.exact[k] = shadowed ? 0.0 : 1.0;
    }
  return f;
}

struct Error {
  double mean = 0.0;  // mean |visibility - exact|
  size_t wrong = 0;   // pixels off by more than a half
  size_t pixels = 0;
};

Error against(const Floor& f, const std::vector<double>& visibility) {
  Error e;
  for (size_t k = 0; k < f.exact.size(); ++k) {
    if (f.exact[k] < 0.0) continue;
    const double d = std::abs(visibility[k] - f.exact[k]);
    e.mean += d, e.wrong += d > 0.5, ++e.pixels;
  }
  if (e.pixels) e.mean /= double(e.pixels);
  return e;
}

void setUp(session::Session& s, const char* path) {
  s.loadScene(contentFile("contact_shadows.gltf"));
  s.setPath(path);
  s.setSize(kSize, kSize);
  s.setView(viewFromAbove());
  session::Lighting light = s.lighting();
  light.sunAngularRadius = 0.00465f;  // the real sun: the closed form's penumbrae
  s.setLighting(light);
  s.settings().materials = lighting::MaterialMode::Diffuse;  // Lambert: the direct path's image gives its visibility
  // A map whose texel is about a pixel (2.5 cm), as a large scene's map is: its filter and bias show.
  s.settings().shadowMapSize = 256;
}

}  // namespace

TEST_F(RayTracingTest, HybridShadowsMatchTheClosedFormAtTheContact) {
  auto& s = session();
  // The map the direct path shadows with: radiance = 0.8 / pi (E n.l V + pi L) on the floor
  // (Lambert, an unoccluded sky of 1 in the direct path), so V = (pi radiance / 0.8 - pi) / (E n.l).
  setUp(s, "direct");
  s.requestBuffer("gbuffer.normal");
  s.requestBuffer(lighting::kShadowSunVisibility);
  s.renderFrames(1);
  const std::vector<float> normals = s.buffer("gbuffer.normal").texels();
  const std::vector<float> hdr = s.buffer(lighting::kCompositeHdr).texels();
  const Floor floor = closedForm(viewFromAbove(), normals);
  std::vector<double> mapped(kSize * kSize);
  for (size_t k = 0; k < mapped.size(); ++k)
    mapped[k] = (double(shared::kPi) * double(hdr[4 * k + 1]) / 0.8 - double(shared::kPi)) / (10.0 * 0.8);
  const Error map = against(floor, mapped);
  EXPECT_FALSE(s.hasBuffer(lighting::kShadowSunVisibility)) << "no top level in the direct path: no hybrid pass";

  setUp(s, "rt");
  s.settings().hybridShadows = true;
  s.requestBuffer(lighting::kShadowSunVisibility);
  s.renderFrames(1);
  ASSERT_TRUE(s.hasBuffer(lighting::kShadowSunVisibility));
  const std::vector<float> v = s.buffer(lighting::kShadowSunVisibility).texels();
  const Error hybrid = against(floor, std::vector<double>(v.begin(), v.end()));

  RecordProperty("pixels", std::to_string(hybrid.pixels));
  RecordProperty("hybrid_mean_error", std::to_string(hybrid.mean));
  RecordProperty("map_mean_error", std::to_string(map.mean));
  RecordProperty("hybrid_wrong", std::to_string(hybrid.wrong));
  RecordProperty("map_wrong", std::to_string(map.wrong));
  ASSERT_GT(hybrid.pixels, kSize * kSize / 4) << "the closed form must cover most of the image";
  EXPECT_LT(hybrid.mean, 0.005) << "the hybrid shadow's visibility against the closed form";
  EXPECT_EQ(hybrid.wrong, 0u);
  EXPECT_GT(map.mean, 4.0 * hybrid.mean) << "the map's shadow, lifted off the contact and filtered, must be worse";
}

TEST_F(RayTracingTest, HybridShadowsKeepTheMapsPenumbraWhereItIsWide) {
  auto& s = session();
  setUp(s, "rt");
  session::Lighting light = s.lighting();
  light.sunAngularRadius = 0.05f;  // about 3 degrees: the shadow's far end has a 12 cm penumbra
  s.setLighting(light);
  s.settings().hybridShadows = true;
  auto fractional = [&](float hardTexels) {
    s.settings().hybridShadowHardTexels = hardTexels;
    s.requestBuffer(lighting::kShadowSunVisibility);
    s.renderFrames(1);
    size_t n = 0;
    for (float x : s.buffer(lighting::kShadowSunVisibility).texels()) n += x > 0.1f && x < 0.9f;
    return n;
  };
  const size_t blended = fractional(4.0f), rayOnly = fractional(64.0f);
  RecordProperty("penumbra_pixels_blended", std::to_string(blended));
  RecordProperty("penumbra_pixels_ray_dominated", std::to_string(rayOnly));
  EXPECT_GT(blended, 2 * rayOnly + 20) << "where the penumbra is wide the map's soft shadow must show";
}

// The pass cannot test a cut-out's alpha: content/cutout.gltf (a fully cut-out card over a floor
// under an overhead sun) keeps the map, and its floor the open floor's light.
TEST_F(RayTracingTest, HybridShadowsLeaveScenesWithCutOutsToTheMap) {
  auto& s = session();
  s.loadScene(contentFile("cutout.gltf"));
  s.setPath("rt");
  s.setSize(64, 64);
  s.settings().hybridShadows = true;
  s.requestBuffer(lighting::kShadowSunVisibility);
  s.renderFrames(1);
  EXPECT_FALSE(s.hasBuffer(lighting::kShadowSunVisibility));
}

}  // namespace tl::test
