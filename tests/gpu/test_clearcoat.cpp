// KHR_materials_clearcoat in the reference on content/clearcoat_probe.gltf: black, smooth
// dielectric quads under a uniform sky of 1, seen from above. Head-on the bare one reflects
// Fresnel's 0.04 of the sky; under a full, smooth coat the light meets two interfaces of ior 1.5,
// 1 - (1 - 0.04)^2 = 0.0784 (closed forms). The G-buffer paths render the base without its coat
// (a line of the scene report): their figures are printed. The coat's energy is held by the
// glass furnace (test_transmission.cpp) and the BRDF's unit tests.
#include <cstdio>
#include <map>
#include <string>

#include "gpu_fixture.h"

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
    const auto image = s.buffer(finalImageOf(path)).texels();
    const uint32_t channels = s.buffer(finalImageOf(path)).channels();
    const auto ids = s.buffer("gbuffer.instanceId").texels();
    // Each quad's pixels away from its edges (all 8 neighbours on the same quad).
    std::map<std::string, std::pair<double, size_t>> sums;
    for (uint32_t y = 1; y + 1 < height; ++y)
      for (uint32_t x = 1; x + 1 < width; ++x) {
        const float id = ids[size_t(y) * width + x];
        if (id == 0.0f) continue;
        bool inside = true;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) inside &= ids[size_t(int(y) + dy) * width + size_t(int(x) + dx)] == id;
        if (!inside) continue;
        auto& e = sums[s.scene().instances[size_t(id) - 1].name];
        e.first += image[(size_t(y) * width + x) * channels + 1];
        ++e.second;
      }
    for (const auto& [name, expected] :
         {std::pair<const char*, double>{"black_bare", 0.04}, {"black_coated", 0.0784}}) {
      ASSERT_GT(sums[name].second, 20u) << name;
      const double mean = sums[name].first / double(sums[name].second);
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
