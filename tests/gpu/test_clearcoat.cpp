// KHR_materials_clearcoat in the reference on content/clearcoat_probe.gltf: black, smooth
// dielectric quads under a uniform sky of 1, seen from above. Head-on the bare one reflects
// Fresnel's 0.04 of the sky; under a full, smooth coat the light meets two interfaces of ior 1.5,
// 1 - (1 - 0.04)^2 = 0.0784 (closed forms). The G-buffer paths render the base without its coat
// (a line of the scene report): their figures are printed. The coat's energy is held by the
// glass furnace (test_transmission.cpp) and the BRDF's unit tests.
#include "gpu_fixture.h"

#include <cstdio>
#include <string>

namespace tl::test {
namespace {

class ClearcoatTest : public RayTracingTest {};

TEST_F(ClearcoatTest, ACoatAddsASecondInterfaceInTheReference) {
  auto& s = session();
  s.loadScene(contentFile("clearcoat_probe.gltf"));
  const uint32_t width = 160, height = 90;
  s.settings().referenceSamplesPerFrame = 16;
  for (const char* path : {"rt", "reference"}) {
    renderFresh(s, path, width, height, std::string(path) == "reference" ? 2 : 16, {"gbuffer.instanceId"});
    // Each quad's pixels away from its edges.
    auto means = interiorMeanByInstance(s, finalImageOf(path));
    for (const auto& [name, expected] :
         {std::pair<const char*, double>{"black_bare", 0.04}, {"black_coated", 0.0784}}) {
      ASSERT_GT(means[name].pixels, 20u) << name;
      const double mean = means[name].rgb.g;
      std::printf("[ clearcoat ] %-9s %-12s %.5f, closed form %.5f (%+.2f%%)\n", path, name, mean, expected,
                  100.0 * (mean / expected - 1.0));
      if (std::string(path) == "reference") {
        EXPECT_NEAR(mean / expected, 1.0, 0.02) << name;
      }
    }
  }
}

}  // namespace
}  // namespace tl::test
