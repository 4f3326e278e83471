// The albedo baker on the GPU: known materials bake to known colours, repeatably; a batch
// cut short resumes to the same database; shards merged equal one bake.
#include "albedo/bake_job.h"
#include "gpu_fixture.h"
#include "lighting_checks.h"
#include "scene/material_average.h"
#include "shared/albedo.h"
#include "shared/rt.h"
#include "../common/test_scenes.h"

namespace tl::test {
namespace {

namespace fs = std::filesystem;
using albedo::BakedEntry;

class AlbedoBakeTest : public GpuTest {
 protected:
  // Bakes every combination of `scene`; fails the test on any failure.
  std::vector<albedo::BakeOutcome> bake(const scene::Scene& scene, albedo::BakeSettings settings = {}) {
    scene::GpuScene gpuScene(session().device(), scene);
    albedo::AlbedoBaker baker(session().device(), scene, gpuScene, settings);
    albedo::SceneKeys keys = albedo::sceneKeys(scene, settings);
    std::vector<albedo::BakeOutcome> out;
    for (auto& c : keys.combinations) {  // one at a time: any batching bakes the same values
      auto one = baker.bake({&c});
      out.push_back(one[0]);
    }
    return out;
  }
  BakedEntry bakeOne(const scene::Scene& scene) {
    auto outcomes = bake(scene);
    EXPECT_EQ(outcomes.size(), 1u);
    EXPECT_TRUE(outcomes[0].entry) << outcomes[0].error;
    return outcomes[0].entry.value_or(BakedEntry{});
  }
  static fs::path tempDb(const std::string& name) {
    fs::path p = fs::path(::testing::TempDir()) / ("twinlight_bake_" + name);
    fs::remove(p);
    return p;
  }
};

scene::Material material(glm::vec3 colour, float metallic = 0.0f) {
  scene::Material m;
  m.name = "m";
  m.baseColorFactor = glm::vec4(colour, 1.0f);
  m.metallic = metallic;
  return m;
}

void expectNear(glm::vec3 a, glm::vec3 b, float tol) {
  EXPECT_NEAR(a.r, b.r, tol);
  EXPECT_NEAR(a.g, b.g, tol);
  EXPECT_NEAR(a.b, b.b, tol);
}

TEST_F(AlbedoBakeTest, WhiteMeshBakesToWhiteWithFullCoverageOfItsSquare) {
  auto s = makeCubeScene(material(glm::vec3(1.0f)));
  BakedEntry e = bakeOne(*s);
  expectNear(e.rgb, glm::vec3(1.0f), 1e-4f);
  // A cube face fills (1 / 1.02)^2 of its tile (2% margin); every view sees one.
  for (float c : e.viewCoverage) EXPECT_NEAR(c, 1.0f / (1.02f * 1.02f), 0.03f);
  EXPECT_LT(e.viewVariance, 1e-8f);
}

TEST_F(AlbedoBakeTest, CheckerboardBakesToItsMean) {
  auto s = makeCubeScene(material(glm::vec3(1.0f)));
  s->textures.push_back(makeCheckerTexture(64, 8, {255, 255, 255}, {0, 0, 0}));
  s->materials[0].baseColorTexture = scene::TextureRef{0};
  BakedEntry e = bakeOne(*s);
  // Texels decode from sRGB to 1 and 0: mean 0.5, through the dielectric F0 rule.
  const glm::vec3 expected = shared::tlRtHitAlbedoFromMaterial(glm::vec3(0.5f), 0.0f);
  expectNear(e.rgb, expected, 0.01f);
  expectNear(e.rgb, scene::materialAverageAlbedo(*s, s->materials[0]), 0.01f);
}

TEST_F(AlbedoBakeTest, MetalsFollowTheF0Rule) {
  const glm::vec3 gold(0.9f, 0.6f, 0.2f);
  BakedEntry metal = bakeOne(*makeCubeScene(material(gold, 1.0f)));
  expectNear(metal.rgb, gold, 1e-4f);  // diffuse 0, F0 = base colour
  BakedEntry half = bakeOne(*makeCubeScene(material(gold, 0.5f)));
  expectNear(half.rgb, shared::tlRtHitAlbedoFromMaterial(gold, 0.5f), 1e-4f);
  BakedEntry dielectric = bakeOne(*makeCubeScene(material(gold, 0.0f)));
  expectNear(dielectric.rgb, gold * 0.96f + 0.04f, 1e-4f);
}

TEST_F(AlbedoBakeTest, ViewsThatSeeDifferentColoursShowVariance) {
  // A 2x2 checker: the +-X faces sample its black cell, the others its white one.
  auto s = makeCubeScene(material(glm::vec3(1.0f)));
  s->textures.push_back(makeCheckerTexture(64, 2, {255, 255, 255}, {0, 0, 0}));
  s->materials[0].baseColorTexture = scene::TextureRef{0};
  for (int v = 0; v < 8; ++v) s->meshes[0].vertices[v].uv = glm::vec2(0.75f, 0.25f);  // black cell: +-X faces
  for (int v = 8; v < 24; ++v) s->meshes[0].vertices[v].uv = glm::vec2(0.25f);         // white cell: the others
  BakedEntry e = bakeOne(*s);
  EXPECT_GT(e.viewVariance, 0.05f) << "views disagree: high view variance";
  // Constant UVs per face: zero texture gradients still sample the right texel.
  EXPECT_NEAR(e.rgb.r, (2.0f * 0.04f + 4.0f * 1.0f) / 6.0f, 0.01f);
}

// A material cut out everywhere: no texel is seen, no ray can hit it. The outcome says so, and a
// bake of a scene holding one finishes without a failure (`bake --scene content/*.gltf` exited 1
// on two shipped scenes with such meshes).
TEST_F(AlbedoBakeTest, AFullyCutOutMaterialIsInvisibleNotAFailure) {
  auto s = makeCubeScene(material(glm::vec3(1.0f)));
  s->materials[0].baseColorFactor.a = 0.1f;
  s->materials[0].alphaMode = scene::AlphaMode::Mask;
  s->materials[0].alphaCutoff = 0.5f;
  auto outcomes = bake(*s);
  ASSERT_EQ(outcomes.size(), 1u);
  EXPECT_FALSE(outcomes[0].entry);
  EXPECT_TRUE(outcomes[0].invisible);
  EXPECT_NE(outcomes[0].error.find("nothing visible"), std::string::npos);

  scene::GpuScene gpuScene(session().device(), *s);
  albedo::AlbedoDatabase db(tempDb("cut_out.db"));
  albedo::BakeJob job(session().device(), *s, gpuScene, db, {});
  while (job.step()) {
  }
  EXPECT_EQ(job.progress().failed, 0u);
  EXPECT_EQ(job.progress().invisible, 1u);
  EXPECT_EQ(job.progress().done, job.progress().total);
  ASSERT_EQ(job.progress().invisibleKeys.size(), 1u);
  EXPECT_TRUE(db.baked().empty()) << "nothing made up is stored for it";
}

TEST_F(AlbedoBakeTest, BakingTwiceGivesIdenticalValues) {
  const scene::Scene atrium = scene::loadGltf(contentFile("atrium.gltf"));
  auto a = bake(atrium), b = bake(atrium);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GE(a.size(), 10u);
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_TRUE(a[i].entry && b[i].entry);
    EXPECT_EQ(a[i].entry->rgb, b[i].entry->rgb) << a[i].entry->label;
    EXPECT_EQ(a[i].entry->viewCoverage, b[i].entry->viewCoverage);
    EXPECT_EQ(a[i].entry->viewVariance, b[i].entry->viewVariance);
  }
}

// Every baked row equal in value (bake times aside).
void expectSameBakes(const albedo::AlbedoDatabase& x, const albedo::AlbedoDatabase& y) {
  auto a = x.baked(), b = y.baked();
  ASSERT_EQ(a.size(), b.size());
  for (auto& [key, row] : a) {
    ASSERT_TRUE(b.count(key)) << albedo::keyToHex(key);
    EXPECT_EQ(row.rgb, b[key].rgb) << row.label << " " << row.rgb.r << " vs " << b[key].rgb.r << " cov " << row.coverage << " vs " << b[key].coverage;
    EXPECT_EQ(row.viewCoverage, b[key].viewCoverage);
    EXPECT_EQ(row.label, b[key].label);
  }
}

TEST_F(AlbedoBakeTest, ABakeCutShortResumesToTheSameDatabase) {
  const scene::Scene atrium = scene::loadGltf(contentFile("atrium.gltf"));
  scene::GpuScene gpuScene(session().device(), atrium);
  albedo::AlbedoDatabase whole(tempDb("whole.db"));
  {
    albedo::BakeJob job(session().device(), atrium, gpuScene, whole, {});
    while (job.step()) {
    }
    EXPECT_EQ(job.progress().failed, 0u);
    EXPECT_EQ(job.progress().baked, job.progress().total);
  }

  albedo::AlbedoDatabase resumed(tempDb("resumed.db"));
  albedo::BakeOptions dies;
  dies.batchSize = 3;
  dies.beforeCommit = [](uint32_t batch) {
    if (batch == 2) throw std::runtime_error("killed inside the transaction");
  };
  {
    albedo::BakeJob job(session().device(), atrium, gpuScene, resumed, dies);
    EXPECT_THROW(
        while (job.step()) {},
        std::runtime_error);
  }
  EXPECT_EQ(resumed.baked().size(), 6u) << "two whole batches, nothing of the third";
  albedo::BakeOptions again;
  again.batchSize = 3;
  albedo::BakeJob job(session().device(), atrium, gpuScene, resumed, again);
  EXPECT_EQ(job.progress().skipped, 6u);
  while (job.step()) {
  }
  EXPECT_EQ(job.progress().baked + job.progress().skipped, job.progress().total);
  expectSameBakes(whole, resumed);
}

TEST_F(AlbedoBakeTest, ShardsMergedEqualOneBake) {
  const scene::Scene atrium = scene::loadGltf(contentFile("atrium.gltf"));
  scene::GpuScene gpuScene(session().device(), atrium);
  albedo::AlbedoDatabase whole(tempDb("shard_whole.db"));
  {
    albedo::BakeJob job(session().device(), atrium, gpuScene, whole, {});
    while (job.step()) {
    }
  }
  std::vector<std::unique_ptr<albedo::AlbedoDatabase>> shards;
  uint32_t total = 0;
  for (uint32_t i = 0; i < 3; ++i) {
    shards.push_back(std::make_unique<albedo::AlbedoDatabase>(tempDb("shard" + std::to_string(i) + ".db")));
    albedo::BakeOptions o;
    o.shardIndex = i;
    o.shardCount = 3;
    albedo::BakeJob job(session().device(), atrium, gpuScene, *shards.back(), o);
    while (job.step()) {
    }
    total += job.progress().total;
  }
  EXPECT_EQ(total, whole.baked().size()) << "shards cover every key once";
  albedo::AlbedoDatabase merged(tempDb("merged.db"));
  for (auto& s : shards) EXPECT_TRUE(merged.mergeFrom(*s).conflicts.empty());
  expectSameBakes(whole, merged);
}

}  // namespace
}  // namespace tl::test

namespace tl::test {
namespace {

class AlbedoOverrideTest : public RayTracingTest {};

// An artist repaints cornell's red wall green. The very next frame's hit records (real
// rays and pre-traced ones alike) carry the new albedo, and once the bounce has settled the
// floor beside the wall is far less red. Undo restores the frame exactly.
TEST_F(AlbedoOverrideTest, AnOverrideChangesRtColourBleedingOnTheNextFrame) {
  auto& s = session();
  s.loadScene(contentFile("cornell.gltf"));
  s.settings().rtDenoise = false;
  auto& lib = s.albedo();
  uint32_t red = ~0u;
  for (uint32_t c = 0; c < lib.entries().size(); ++c)
    if (lib.entries()[c].combination.label.find("cornell_red") != std::string::npos) red = c;
  ASSERT_NE(red, ~0u) << "cornell has a red wall";
  auto settledLeftRedToGreen = [&] {
    s.resetHistory();
    s.setFrameIndex(7);
    return cornellBleeding(s, "rt", "rt.gi.temporal.shY", "rt.gi.temporal.coCgAo", 12).left;
  };
  auto redHits = [&] {
    s.requestBuffer("rt.hits");
    s.renderFrames(1);
    const auto& rb = s.buffer("rt.hits");
    const auto* h = reinterpret_cast<const uint32_t*>(rb.bytes.data());
    size_t n = 0;
    for (size_t i = 0; i < rb.bytes.size() / 4; ++i) {
      const glm::vec3 a = shared::tlRtHitAlbedo(h[i]);
      n += shared::tlRtIsHit(h[i]) && a.r > 0.4f && a.g < 0.2f;
    }
    return n;
  };
  const double before = settledLeftRedToGreen();
  EXPECT_GT(redHits(), 50u) << "rays from the floor and boxes hit the red wall";
  lib.setOverride(red, glm::vec3(0.05f, 0.6f, 0.05f));
  EXPECT_EQ(redHits(), 0u) << "the next frame's hits all read the override";
  const double after = settledLeftRedToGreen();
  RecordProperty("left_red_to_green_before", std::to_string(before));
  RecordProperty("left_red_to_green_after", std::to_string(after));
  EXPECT_GT(before, 1.2);
  EXPECT_LT(after, 0.85 * before) << "the floor by the repainted wall loses its red";
  ASSERT_TRUE(lib.undo());
  EXPECT_EQ(settledLeftRedToGreen(), before) << "undo restores the frame exactly";
}

}  // namespace
}  // namespace tl::test

namespace tl::test {
namespace {

class AlbedoViewTest : public GpuTest {};

bool ranPass(const session::Session& s, const std::string& name) {
  for (const auto& t : s.timings())
    if (t.pass == name) return true;
  return false;
}

// albedo.instance shows the albedo rays read and its source; albedo.difference is ~0 where
// the fallback (texture average) of untextured materials applies and large under an
// override; neither costs anything unless something reads it.
TEST_F(AlbedoViewTest, InstanceAndDifferenceViewsFollowTheResolution) {
  auto& s = session();
  s.loadScene(contentFile("cornell.gltf"));
  s.setSize(48, 48);
  s.renderFrames(1);
  EXPECT_FALSE(ranPass(s, "albedo.view")) << "culled when nothing reads it";

  auto views = [&] {
    s.requestBuffer("albedo.instance");
    s.requestBuffer("albedo.difference");
    s.requestBuffer("gbuffer.instanceId");
    s.renderFrames(1);
    EXPECT_TRUE(ranPass(s, "albedo.view"));
  };
  views();
  auto inst = s.buffer("albedo.instance").texels(), diff = s.buffer("albedo.difference").texels();
  size_t surface = 0;
  float worst = 0.0f;
  for (size_t i = 0; i < inst.size() / 4; ++i) {
    if (inst[4 * i + 3] == 0.0f) continue;
    ++surface;
    EXPECT_EQ(inst[4 * i + 3], shared::kAlbedoSourceTextureAverage);
    worst = std::max({worst, diff[4 * i], diff[4 * i + 1], diff[4 * i + 2]});
  }
  ASSERT_GT(surface, 1000u);
  EXPECT_LT(worst, 0.01f) << "untextured materials: fallback = G-buffer albedo up to 8-bit sRGB";

  auto& lib = s.albedo();
  uint32_t red = 0;
  for (uint32_t c = 0; c < lib.entries().size(); ++c)
    if (lib.entries()[c].combination.label.find("cornell_red") != std::string::npos) red = c;
  lib.setOverride(red, glm::vec3(0.0f, 0.0f, 1.0f));
  views();
  inst = s.buffer("albedo.instance").texels();
  diff = s.buffer("albedo.difference").texels();
  const auto ids = s.buffer("gbuffer.instanceId");
  const auto* id = reinterpret_cast<const uint32_t*>(ids.bytes.data());
  const uint32_t redInstance = lib.entries()[red].combination.instances[0] + 1;
  size_t overridden = 0;
  for (size_t i = 0; i < inst.size() / 4; ++i) {
    if (id[i] != redInstance) continue;
    ++overridden;
    EXPECT_EQ(inst[4 * i + 3], shared::kAlbedoSourceOverride);
    EXPECT_EQ(inst[4 * i + 2], 1.0f);
    EXPECT_GT(diff[4 * i + 2], 0.8f) << "blue override vs red texels";
  }
  EXPECT_GT(overridden, 50u);
  lib.undo();
}

// albedo.impact: zero before any edit, and where the edit changed the bounce afterwards.
TEST_F(AlbedoViewTest, ImpactViewShowsWhatAnEditChanged) {
  auto& s = session();
  if (!s.device().rayTracing().pipeline) GTEST_SKIP() << "needs the RT path";
  s.loadScene(contentFile("cornell.gltf"));
  s.setSize(48, 48);
  s.setPath("rt");
  s.settings().rtDenoise = false;
  s.renderFrames(16);
  s.captureAlbedoBaseline();
  s.requestBuffer("albedo.impact");
  s.renderFrames(1);
  auto meanImpact = [&] {
    double sum = 0.0;
    auto t = s.buffer("albedo.impact").texels();
    for (size_t i = 0; i < t.size() / 4; ++i) sum += t[4 * i] + t[4 * i + 1] + t[4 * i + 2];
    return sum / double(t.size() / 4);
  };
  const double still = meanImpact();
  auto& lib = s.albedo();
  for (uint32_t c = 0; c < lib.entries().size(); ++c)
    if (lib.entries()[c].combination.label.find("cornell_red") != std::string::npos) lib.setOverride(c, glm::vec3(0.0f, 0.8f, 0.0f));
  s.requestBuffer("albedo.impact");
  s.renderFrames(16);
  const double edited = meanImpact();
  RecordProperty("impact_before_edit", std::to_string(still));
  RecordProperty("impact_after_edit", std::to_string(edited));
  EXPECT_GT(edited, 5.0 * still + 1e-3) << "before " << still << ", after " << edited;
  lib.undo();
}

}  // namespace
}  // namespace tl::test
