// Soft sun shadows (PCSS): a larger sun gives wider penumbrae on the atrium's floor.
#include "gpu_fixture.h"

#include "shared/common.h"
#include "shared/packing.h"

#include <algorithm>

namespace tl::test {
namespace {

struct Floor {
  std::vector<float> luminance;  // per floor pixel
  float lit = 0.0f;              // 95th percentile: fully sunlit floor
};

Floor floorLuminance(session::Session& s) {
  s.requestBuffer("composite.hdr");
  s.requestBuffer("gbuffer.normal");
  s.renderFrames(1);
  auto c = s.buffer("composite.hdr").texels(), n = s.buffer("gbuffer.normal").texels();
  Floor f;
  for (size_t i = 0; i < n.size() / 2; ++i) {
    const bool floor = shared::tlOctDecode(glm::vec2(n[2 * i], n[2 * i + 1])).y > 0.95f;
    f.luminance.push_back(floor ? shared::tlLuminance(glm::vec3(c[4 * i], c[4 * i + 1], c[4 * i + 2])) : -1.0f);
  }
  std::vector<float> sorted;
  for (float v : f.luminance)
    if (v >= 0.0f) sorted.push_back(v);
  std::sort(sorted.begin(), sorted.end());
  f.lit = sorted[sorted.size() * 95 / 100];
  return f;
}

// Floor pixels that differ by more than 5% of the sunlit floor: where the shadows' edges moved.
size_t changed(const Floor& a, const Floor& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.luminance.size(); ++i)
    n += a.luminance[i] >= 0.0f && std::abs(a.luminance[i] - b.luminance[i]) > 0.05f * a.lit;
  return n;
}

TEST_F(GpuTest, LargerSunGivesWiderPenumbrae) {
  auto& s = session();
  s.loadScene(contentFile("atrium.gltf"));
  s.setPath("direct");
  s.setSize(320, 180);
  session::Lighting light = s.lighting();
  light.sunAngularRadius = 0.00465f;  // the real sun: penumbrae of a texel or two
  s.setLighting(light);
  const Floor sharp = floorLuminance(s);
  s.settings().softShadows = false;
  const Floor pcf = floorLuminance(s);
  s.settings().softShadows = true;
  light.sunAngularRadius = 0.05f;  // about 3 degrees
  s.setLighting(light);
  const Floor soft = floorLuminance(s);
  const size_t real = changed(sharp, pcf), widened = changed(sharp, soft);
  RecordProperty("pixels_changed_real_sun_vs_pcf", std::to_string(real));
  RecordProperty("pixels_changed_3deg_sun", std::to_string(widened));
  EXPECT_LT(real * 10, widened) << "the real sun's penumbra is about a texel: nearly PCF";
  EXPECT_GT(widened, 200u) << "a 3 degree sun must soften the shadow edges";
}

}  // namespace
}  // namespace tl::test
