// The glTF probe scenes of content/ as the G-buffer sees them (every path shades from it):
//   - embedded_textures.glb: both images come out of the .glb, the 16-bit emissive keeps its
//     value on the GPU (1.51, where 8 bits give 0);
//   - normal_probe.gltf: the normal map leans every quad's normal the way the closed form
//     says — towards -dP/dv (the map's green, the image's top) and along dP/du (its red) —
//     whether the tangents were supplied by the file or generated on import;
//   - texture_transform_probe, sampler_probe, texcoord1_probe: the texel of a 2x2 image that
//     lands at a point of a quad is the one the closed form (the transform, the wrap, the UV
//     set) names;
//   - color0_probe: COLOR_0 multiplies the base colour in the G-buffer and at the reference's
//     hits, and its alpha cuts a MASK material out;
//   - normal_probe again: the reference's hits lean their normals as the G-buffer does.
#include "gpu_fixture.h"

#include "shared/color.h"
#include "shared/packing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace tl::test {
namespace {

using GltfProbeTest = GpuTest;

TEST_F(GltfProbeTest, EmbeddedTexturesReachTheGbufferAtTheirPrecision) {
  auto& s = session();
  s.loadScene(contentFile("embedded_textures.glb"));
  EXPECT_TRUE(s.scene().warnings.empty()) << s.scene().warnings.front();
  s.setSize(32, 32);
  s.requestBuffer("gbuffer.baseColor");
  s.requestBuffer("gbuffer.emissive");
  s.renderFrames(1);
  const auto base = s.buffer("gbuffer.baseColor").texels();    // sRGB as stored
  const auto glow = s.buffer("gbuffer.emissive").texels();
  const size_t left = (16 * 32 + 8) * 4, right = (16 * 32 + 24) * 4;
  EXPECT_NEAR(base[left + 0], 188.0f / 255.0f, 1.5f / 255.0f);
  EXPECT_NEAR(base[left + 1], 94.0f / 255.0f, 1.5f / 255.0f);
  EXPECT_NEAR(base[left + 2], 47.0f / 255.0f, 1.5f / 255.0f);
  const float expected = shared::tlSrgbToLinear1(128.0f / 65535.0f) * 1.0e4f;  // 1.5118
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(glow[right + size_t(c)] / expected, 1.0f, 0.01f) << "channel " << c;
  EXPECT_EQ(glow[left], 0.0f) << "the base-colour quad does not glow";
}

TEST_F(GltfProbeTest, NormalMapLeansTheClosedFormWayWithAndWithoutTangents) {
  auto& s = session();
  s.loadScene(contentFile("normal_probe.gltf"));
  EXPECT_TRUE(s.scene().warnings.empty()) << s.scene().warnings.front();
  s.setSize(96, 54);
  s.requestBuffer("gbuffer.normal");
  s.requestBuffer("gbuffer.instanceId");
  s.renderFrames(1);
  const auto normals = s.buffer("gbuffer.normal").texels();
  const auto ids = s.buffer("gbuffer.instanceId").texels();
  // The map's texel (8-bit, as stored) in tangent space, and the closed form per quad:
  // n = normalize(T x + B y + N z) with N = +Y, B = -dP/dv = +Z, T = dP/du = +X or -X (mirrored).
  glm::vec3 tn(0.0f);
  const glm::vec3 exact = glm::normalize(glm::vec3(0.3f, 0.5f, 0.81f));
  for (int c = 0; c < 3; ++c) tn[c] = std::round((exact[c] * 0.5f + 0.5f) * 255.0f) / 255.0f * 2.0f - 1.0f;
  const auto& scene = s.scene();
  std::map<std::string, std::pair<glm::dvec3, size_t>> seen;
  for (size_t p = 0; p < ids.size(); ++p) {
    const uint32_t id = uint32_t(ids[p]);
    if (id == 0) continue;
    const std::string& name = scene.instances[id - 1].name;
    const glm::vec3 n = shared::tlOctDecode(glm::vec2(normals[2 * p], normals[2 * p + 1]));
    seen[name].first += glm::dvec3(n);
    ++seen[name].second;
  }
  ASSERT_EQ(seen.size(), 4u) << "all four quads in view";
  for (const auto& [name, sum] : seen) {
    const float t = name.rfind("mirrored", 0) == 0 ? -1.0f : 1.0f;
    const glm::vec3 expected = glm::normalize(glm::vec3(t * tn.x, tn.z, tn.y));
    const glm::vec3 mean = glm::normalize(glm::vec3(sum.first / double(sum.second)));
    EXPECT_GT(sum.second, 20u) << name;
    EXPECT_NEAR(mean.x, expected.x, 0.01f) << name;
    EXPECT_NEAR(mean.y, expected.y, 0.01f) << name;
    EXPECT_NEAR(mean.z, expected.z, 0.01f) << name << ": the bump must lean towards the image's top (+Z)";
  }
}

// Where each instance of a top-down probe lies on screen: per row, its leftmost and
// rightmost pixel. A row of the image is a line of constant depth across the ground, so along
// it u is affine in x: u = (x + 0.5 - left) / (right + 1 - left).
struct QuadOnScreen {
  std::map<uint32_t, std::pair<uint32_t, uint32_t>> rows;  // row -> [left, right]
  size_t pixels = 0;
};

std::map<std::string, QuadOnScreen> quadsOnScreen(const scene::Scene& scene, const std::vector<float>& ids, uint32_t width) {
  std::map<std::string, QuadOnScreen> out;
  for (size_t p = 0; p < ids.size(); ++p) {
    const uint32_t id = uint32_t(ids[p]);
    if (id == 0) continue;
    QuadOnScreen& q = out[scene.instances[id - 1].name];
    const uint32_t x = uint32_t(p % width), y = uint32_t(p / width);
    auto [it, added] = q.rows.try_emplace(y, x, x);
    it->second.first = std::min(it->second.first, x);
    it->second.second = std::max(it->second.second, x);
    ++q.pixels;
  }
  return out;
}

// The pixel showing the quad at (u, v): u across its row, v (0 at the near edge, increasing
// away from the camera) as a fraction of its rows, far rows on top.
size_t pixelAt(const QuadOnScreen& q, uint32_t width, float u, float v) {
  const uint32_t top = q.rows.begin()->first, bottom = q.rows.rbegin()->first;
  const uint32_t y = uint32_t(std::lround(float(bottom) - v * float(bottom - top)));
  const auto [left, right] = q.rows.at(y);
  const uint32_t x = uint32_t(std::clamp(std::lround(float(left) - 0.5f + u * float(right + 1 - left)), long(left), long(right)));
  return size_t(y) * width + x;
}

// The quadrant image's texel at texture coordinates already wrapped into [0, 1): red, green
// on the top row (v < 0.5), blue, white below.
glm::vec3 quadrantTexel(glm::vec2 uv) {
  const int column = uv.x < 0.5f ? 0 : 1, row = uv.y < 0.5f ? 0 : 1;
  const glm::vec3 texels[2][2] = {{{1, 0, 0}, {0, 1, 0}}, {{0, 0, 1}, {1, 1, 1}}};
  return texels[row][column];
}

float repeat(float x) { return x - std::floor(x); }

// Renders one frame of a probe at 160x90 and returns base colours (as stored, sRGB) and ids.
struct ProbeFrame {
  std::vector<float> base, ids;
  uint32_t width = 160, height = 90;
};

ProbeFrame renderProbe(session::Session& s, const char* file) {
  s.loadScene(contentFile(file));
  EXPECT_TRUE(s.scene().warnings.empty()) << s.scene().warnings.front();
  EXPECT_TRUE(s.scene().ignored.empty()) << s.scene().ignored.front();
  ProbeFrame f;
  s.setSize(f.width, f.height);
  s.requestBuffer("gbuffer.baseColor");
  s.requestBuffer("gbuffer.instanceId");
  s.renderFrames(1);
  f.base = s.buffer("gbuffer.baseColor").texels();
  f.ids = s.buffer("gbuffer.instanceId").texels();
  return f;
}

glm::vec3 baseAt(const ProbeFrame& f, size_t pixel) { return {f.base[pixel * 4], f.base[pixel * 4 + 1], f.base[pixel * 4 + 2]}; }

void expectTexel(const ProbeFrame& f, const QuadOnScreen& q, float u, float v, glm::vec3 expected, const std::string& what) {
  const glm::vec3 got = baseAt(f, pixelAt(q, f.width, u, v));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 1.5f / 255.0f) << what << " at (" << u << ", " << v << ") channel " << c;
}

TEST_F(GltfProbeTest, TextureTransformPutsEachTexelWhereTheClosedFormSays) {
  auto& s = session();
  const ProbeFrame f = renderProbe(s, "texture_transform_probe.gltf");
  const auto quads = quadsOnScreen(s.scene(), f.ids, f.width);
  ASSERT_EQ(quads.size(), 5u);
  // KHR_texture_transform: uv' = offset + R(rotation) S(scale) uv, worked out per probe.
  const std::map<std::string, glm::vec2 (*)(glm::vec2)> transforms = {
      {"identity", [](glm::vec2 uv) { return uv; }},
      {"offset", [](glm::vec2 uv) { return uv + glm::vec2(0.5f, 0.0f); }},
      {"rotation", [](glm::vec2 uv) { return glm::vec2(uv.y, 1.0f - uv.x); }},  // pi/2, offset (0, 1)
      {"scale", [](glm::vec2 uv) { return glm::vec2(3.0f * uv.x, uv.y); }},
      {"texcoord_override", [](glm::vec2 uv) { return glm::vec2(1.0f - uv.x, uv.y); }}};  // TEXCOORD_1 = (1 - u, v)
  for (const auto& [name, transform] : transforms) {
    ASSERT_TRUE(quads.count(name)) << name;
    for (float u : {0.25f, 0.75f})
      for (float v : {0.25f, 0.75f}) {
        const glm::vec2 t = transform({u, v});
        expectTexel(f, quads.at(name), u, v, quadrantTexel({repeat(t.x), repeat(t.y)}), name);
      }
  }
}

TEST_F(GltfProbeTest, SamplerWrapModesAndFiltersAreTheFilesOwn) {
  auto& s = session();
  const ProbeFrame f = renderProbe(s, "sampler_probe.gltf");
  const auto quads = quadsOnScreen(s.scene(), f.ids, f.width);
  ASSERT_EQ(quads.size(), 5u);
  // u' = 3u - 1 across the wide quads; what each wrap mode makes of it (glTF 3.8.4).
  const std::map<std::string, float (*)(float)> wraps = {
      {"repeat", [](float x) { return repeat(x); }},
      {"clamp", [](float x) { return std::clamp(x, 0.0f, 0.999f); }},
      {"mirror", [](float x) { const float m = x - 2.0f * std::floor(x / 2.0f); return m > 1.0f ? 2.0f - m : m; }}};
  for (const auto& [name, wrap] : wraps)
    for (float wide : {-0.25f, 1.25f, 1.75f})
      for (float v : {0.25f, 0.75f}) expectTexel(f, quads.at(name), (wide + 1.0f) / 3.0f, v, quadrantTexel({wrap(wide), v}), name);
  // Magnified 2x2, on the red-green row (v = 0.25, a texel centre): halfway across LINEAR mixes them half and
  // half (decoded from sRGB before filtering), NEAREST shows one of them whole.
  const glm::vec3 mixed = shared::tlSrgbToLinear(baseAt(f, pixelAt(quads.at("linear"), f.width, 0.5f, 0.25f)));
  EXPECT_NEAR(mixed.r, 0.5f, 0.08f);
  EXPECT_NEAR(mixed.g, 0.5f, 0.08f);
  EXPECT_NEAR(mixed.r + mixed.g, 1.0f, 0.02f);
  const glm::vec3 sharp = baseAt(f, pixelAt(quads.at("nearest"), f.width, 0.5f, 0.25f));
  EXPECT_NEAR(sharp.r + sharp.g, 1.0f, 1.5f / 255.0f);
  EXPECT_NEAR(sharp.r * sharp.g, 0.0f, 1e-3f) << "nearest: one texel, not a mix";
}

TEST_F(GltfProbeTest, TexCoordOneReadsTheSecondUvSet) {
  auto& s = session();
  const ProbeFrame f = renderProbe(s, "texcoord1_probe.gltf");
  const auto quads = quadsOnScreen(s.scene(), f.ids, f.width);
  ASSERT_EQ(quads.size(), 1u);
  for (float u : {0.25f, 0.75f})
    for (float v : {0.25f, 0.75f}) expectTexel(f, quads.begin()->second, u, v, quadrantTexel({u, v}), "second_uv_set");
}

TEST_F(GltfProbeTest, VertexColourMultipliesTheBaseColourAndItsAlphaCutsOut) {
  auto& s = session();
  const ProbeFrame f = renderProbe(s, "color0_probe.gltf");
  const auto quads = quadsOnScreen(s.scene(), f.ids, f.width);
  EXPECT_EQ(quads.count("cut_out"), 0u) << "COLOR_0 alpha 0 under a MASK cutoff of 0.5";
  const std::map<std::string, glm::vec3> colours = {
      {"white", {1, 1, 1}}, {"black", {0, 0, 0}}, {"red", {1, 0, 0}}, {"green", {0, 1, 0}}, {"blue", {0, 0, 1}}};
  for (const auto& [name, colour] : colours) {
    ASSERT_TRUE(quads.count(name)) << name;
    const glm::vec3 base = shared::tlSrgbToLinear(baseAt(f, pixelAt(quads.at(name), f.width, 0.5f, 0.5f)));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(base[c], 0.5f * colour[c], 0.006f) << name << " channel " << c;
  }
}

using GltfProbeRayTest = RayTracingTest;

// The reference shades its hits with the same COLOR_0: under the sky alone a lone quad
// reflects a rho + s, so (L_colour - L_black) / (L_white - L_black) is the colour.
TEST_F(GltfProbeRayTest, ReferenceHitsMultiplyTheVertexColour) {
  auto& s = session();
  s.loadScene(contentFile("color0_probe.gltf"));
  s.setPath("reference");
  const uint32_t width = 160, height = 90;
  s.setSize(width, height);
  s.settings().referenceSamplesPerFrame = 4;
  s.setFrameIndex(0);
  s.resetHistory();
  s.renderFrames(3);
  s.requestBuffer("reference.radiance");
  s.requestBuffer("gbuffer.instanceId");
  s.renderFrames(1);
  const auto radiance = s.buffer("reference.radiance").texels();
  const auto ids = s.buffer("gbuffer.instanceId").texels();
  const auto quads = quadsOnScreen(s.scene(), ids, width);
  EXPECT_EQ(quads.count("cut_out"), 0u);
  // Mean radiance over the middle of each quad (rows and columns a quarter in).
  auto mean = [&](const std::string& name) {
    const QuadOnScreen& q = quads.at(name);
    glm::dvec3 sum(0.0);
    size_t n = 0;
    for (float u = 0.3f; u <= 0.71f; u += 0.1f)
      for (float v = 0.3f; v <= 0.71f; v += 0.1f) {
        const size_t p = pixelAt(q, width, u, v);
        sum += glm::dvec3(radiance[p * 4], radiance[p * 4 + 1], radiance[p * 4 + 2]);
        ++n;
      }
    return sum / double(n);
  };
  const glm::dvec3 white = mean("white"), black = mean("black");
  const std::map<std::string, glm::dvec3> colours = {{"red", {1, 0, 0}}, {"green", {0, 1, 0}}, {"blue", {0, 0, 1}}};
  for (const auto& [name, colour] : colours) {
    const glm::dvec3 l = mean(name);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR((l[c] - black[c]) / (white[c] - black[c]), colour[c], 0.03) << name << " channel " << c;
  }
}

}  // namespace
}  // namespace tl::test

namespace tl::test {
namespace {

// Mean linear radiance (luminance) of composite.hdr over each named instance's pixels.
std::map<std::string, double> radianceByInstance(session::Session& s) {
  s.requestBuffer("gbuffer.instanceId");
  s.renderFrames(1);
  const auto hdr = s.buffer("composite.hdr").texels();
  const auto ids = s.buffer("gbuffer.instanceId");
  const auto* id = reinterpret_cast<const uint32_t*>(ids.bytes.data());
  std::map<std::string, double> sum, count;
  for (size_t i = 0; i < hdr.size() / 4; ++i) {
    if (id[i] == 0) continue;
    const std::string& name = s.scene().instances.at(id[i] - 1).name;
    sum[name] += shared::tlLuminance(glm::vec3(hdr[4 * i], hdr[4 * i + 1], hdr[4 * i + 2]));
    count[name] += 1.0;
  }
  for (auto& [name, v] : sum) v /= count[name];
  return sum;
}

}  // namespace

// occlusion_probe: glTF's occlusion texture darkens indirect light only. Sky alone, the three
// quads stand 0.251 : 0.6255 : 1 (texel 64/255 at strength 1 and 0.5, none); the sun's share,
// the difference with the sun on, is the same on all three. Deferred and redeferred alike; the
// Lambertian modes leave the texture out.
TEST_F(GltfProbeTest, OcclusionTextureDarkensIndirectLightOnly) {
  auto& s = session();
  s.loadScene(contentFile("occlusion_probe.gltf"));
  EXPECT_TRUE(s.scene().warnings.empty()) << s.scene().warnings.front();
  s.setSize(160, 90);
  const double texel = 64.0 / 255.0;
  for (bool redeferred : {false, true}) {
    SCOPED_TRACE(redeferred ? "redeferred" : "deferred");
    s.settings().redeferred = redeferred;
    const session::Lighting withSun = s.lighting();
    session::Lighting skyOnly = withSun;
    skyOnly.sunIrradiance = glm::vec3(0.0f);
    skyOnly.exposureEv = 0.0f;
    s.setLighting(skyOnly);
    auto sky = radianceByInstance(s);
    session::Lighting sun = withSun;
    sun.exposureEv = 0.0f;
    s.setLighting(sun);
    auto lit = radianceByInstance(s);
    s.setLighting(withSun);
    ASSERT_EQ(sky.size(), 3u);
    ASSERT_GT(sky["plain"], 0.1);
    EXPECT_NEAR(sky["occluded"] / sky["plain"], texel, 0.005);
    EXPECT_NEAR(sky["half_occluded"] / sky["plain"], 1.0 + 0.5 * (texel - 1.0), 0.005);
    const double sunPlain = lit["plain"] - sky["plain"];
    ASSERT_GT(sunPlain, sky["plain"]);
    EXPECT_NEAR((lit["occluded"] - sky["occluded"]) / sunPlain, 1.0, 0.005) << "the sun is not occluded";
    EXPECT_NEAR((lit["half_occluded"] - sky["half_occluded"]) / sunPlain, 1.0, 0.005);
  }
  s.settings().redeferred = false;
  s.settings().materials = lighting::MaterialMode::Diffuse;
  const auto diffuse = radianceByInstance(s);
  EXPECT_NEAR(diffuse.at("occluded") / diffuse.at("plain"), 1.0, 0.005) << "--materials diffuse leaves occlusion out";
}

}  // namespace tl::test

namespace tl::test {
namespace {

// The reference shades a normal-mapped hit with the mapped normal, as the G-buffer does: under a
// sun from +X alone (travelling (-0.6, -0.8, 0)) the quads whose bump leans +X catch more light
// than the mirrored ones leaning -X (Lambert alone: n.l 0.830 against 0.469, 1.77x); with
// vertex normals all four would be equal. Each quad's mean radiance in the reference is the
// direct path's within 3% (same BRDF, one sun, nothing to shadow).
TEST_F(GltfProbeRayTest, ReferenceHitsLeanWithTheNormalMapAsTheGbufferDoes) {
  auto& s = session();
  const uint32_t width = 160, height = 90;
  std::map<std::string, std::map<std::string, double>> means;  // path -> quad -> mean green
  for (const char* path : {"direct", "reference"}) {
    s.loadScene(contentFile("normal_probe.gltf"));
    session::Lighting sunOnly = s.lighting();
    sunOnly.sunDirection = glm::normalize(glm::dvec3(-0.6, -0.8, 0.0));
    sunOnly.sunIrradiance = glm::vec3(10.0f);
    sunOnly.skyRadiance = glm::vec3(0.0f);
    s.setLighting(sunOnly);
    s.settings().referenceSamplesPerFrame = 8;
    renderFresh(s, path, width, height, std::string(path) == "reference" ? 4 : 1, {"gbuffer.instanceId"});
    const auto radiance = s.buffer(finalImageOf(path)).texels();
    const auto quads = quadsOnScreen(s.scene(), s.buffer("gbuffer.instanceId").texels(), width);
    ASSERT_EQ(quads.size(), 4u) << path;
    for (const auto& [name, q] : quads) {
      double sum = 0.0;
      size_t n = 0;
      for (float u = 0.3f; u <= 0.71f; u += 0.1f)
        for (float v = 0.3f; v <= 0.71f; v += 0.1f, ++n) sum += radiance[4 * pixelAt(q, width, u, v) + 1];
      means[path][name] = sum / double(n);
    }
  }
  for (const auto& [name, direct] : means["direct"]) {
    const double reference = means["reference"][name];
    std::printf("[ normals  ] %-18s direct %.4f  reference %.4f  ratio %.4f\n", name.c_str(), direct, reference,
                reference / direct);
    EXPECT_NEAR(reference / direct, 1.0, 0.03) << name;
  }
  for (const char* path : {"direct", "reference"}) {
    auto& m = means[path];
    const double lean = (m["plain_generated"] + m["plain_supplied"]) / (m["mirrored_generated"] + m["mirrored_supplied"]);
    std::printf("[ normals  ] %-9s bump towards the sun / away: %.4f\n", path, lean);
    EXPECT_GT(lean, 1.5) << path << ": the bump must lean towards +X on the plain quads";
  }
}

}  // namespace
}  // namespace tl::test
