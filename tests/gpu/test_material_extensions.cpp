// KHR_materials_ior, KHR_materials_specular and KHR_materials_unlit on content/ior_probe.gltf: black,
// nearly smooth dielectric quads (roughness 0.1) under a uniform sky of radiance 1, seen from
// above. Head-on such a surface reflects Fresnel's reflectance of unpolarised light at normal
// incidence, ((n - 1) / (n + 1))^2, of the sky — a closed form independent of the BRDF's code
// (the lobe's own loss at roughness 0.1 and view angles up to 30 degrees change it by under 1%,
// the G-buffer's 8-bit sqrt(F0) by under 2%). specularFactor 0 reflects nothing; the unlit quad
// shows its base colour, 0.25, whatever the light. Checked in every path and the reference.
#include "gpu_fixture.h"

#include <cstdio>
#include <map>
#include <string>

namespace tl::test {
namespace {

struct Expected {
  const char* name;
  double value;  // radiance seen head-on under a sky of 1
};
double fresnel(double n) { return (n - 1.0) * (n - 1.0) / ((n + 1.0) * (n + 1.0)); }
const Expected kExpected[] = {{"ior_1", 0.0},          {"ior_1_33", fresnel(1.33)}, {"ior_1_5", fresnel(1.5)},
                              {"ior_2", fresnel(2.0)}, {"ior_2_42", fresnel(2.42)}, {"specular_0", 0.0},
                              {"unlit_quarter", 0.25}};

class MaterialExtensionsTest : public RayTracingTest, public ::testing::WithParamInterface<const char*> {};

TEST_P(MaterialExtensionsTest, IorSpecularAndUnlitShowTheirClosedForms) {
  const std::string path = GetParam();
  auto& s = session();
  s.loadScene(contentFile("ior_probe.gltf"));
  EXPECT_TRUE(s.scene().warnings.empty()) << s.scene().warnings.front();
  EXPECT_TRUE(s.scene().ignored.empty()) << s.scene().ignored.front();
  const uint32_t width = 192, height = 108;
  s.settings().referenceSamplesPerFrame = 16;
  renderFresh(s, path, width, height, path == "reference" ? 2 : (path == "direct" ? 1 : 16), {"gbuffer.instanceId"});
  // Each quad's pixels away from its edges: no pixel mixes the sky in.
  auto means = interiorMeanByInstance(s, finalImageOf(path));
  for (const Expected& e : kExpected) {
    ASSERT_GT(means[e.name].pixels, 20u) << e.name;
    const glm::dvec3 rgb = means[e.name].rgb;
    const double mean = (rgb.r + rgb.g + rgb.b) / 3.0;
    std::printf("[ ior ] %-9s %-13s %.5f, closed form %.5f (%+.2f%%)\n", path.c_str(), e.name, mean, e.value,
                e.value > 0.0 ? 100.0 * (mean / e.value - 1.0) : 0.0);
    EXPECT_NEAR(mean, e.value, 0.03 * e.value + 0.002) << path << " " << e.name;
  }
}

INSTANTIATE_TEST_SUITE_P(EveryPath, MaterialExtensionsTest, ::testing::Values("direct", "legacy", "rt", "reference"),
                         [](const auto& info) { return std::string(info.param); });

}  // namespace
}  // namespace tl::test
