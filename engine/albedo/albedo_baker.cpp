#include "albedo/albedo_baker.h"

#include "lighting/common/pass_builders.h"
#include "shared/albedo.h"
#include "shared/scene.h"

#include <fmt/format.h>

#include <algorithm>

namespace tl::albedo {
glm::mat4 bakeViewProjection(const scene::Bounds& bounds, int view) {
  const int axis = view / 2;
  const float side = view % 2 == 0 ? 1.0f : -1.0f;  // +: seen from the positive side
  glm::vec3 lo(bounds.valid() ? bounds.min : glm::dvec3(-1.0)), hi(bounds.valid() ? bounds.max : glm::dvec3(1.0));
  const glm::vec3 centre = (lo + hi) * 0.5f, size = hi - lo;
  glm::vec3 a(0.0f), u(0.0f), v(0.0f);
  a[axis] = 1.0f;
  u[(axis + 1) % 3] = 1.0f;
  v[(axis + 2) % 3] = 1.0f;
  const float largest = std::max({size.x, size.y, size.z, 1e-6f});
  // Square and aspect-preserving, so every texel covers the same area in every view.
  const float half = 0.51f * std::max({size[(axis + 1) % 3], size[(axis + 2) % 3], 1e-4f * largest});
  const float halfDepth = 0.51f * std::max(size[axis], 1e-4f * largest);
  glm::mat4 m(0.0f);  // m[column][row]
  for (int j = 0; j < 3; ++j) {
    m[j][0] = u[j] / half;
    m[j][1] = v[j] / half;
    m[j][2] = 0.5f * side * a[j] / halfDepth;
  }
  m[3][0] = -glm::dot(u, centre) / half;
  m[3][1] = -glm::dot(v, centre) / half;
  m[3][2] = 0.5f - 0.5f * side * glm::dot(a, centre) / halfDepth;
  m[3][3] = 1.0f;
  return m;
}

std::optional<BakedEntry> entryFromViewSums(AlbedoKey key, const std::array<glm::vec4, kViews>& sums, uint32_t tileSize) {
  const double pixels = double(tileSize) * tileSize;
  glm::dvec3 total(0.0);
  double covered = 0.0;
  BakedEntry e;
  e.key = key;
  for (int v = 0; v < kViews; ++v) {
    total += glm::dvec3(sums[v]);
    covered += sums[v].w;
    e.viewCoverage[v] = float(sums[v].w / pixels);
    e.coverage += e.viewCoverage[v] / float(kViews);
  }
  if (covered <= 0.0) return std::nullopt;
  const glm::dvec3 mean = total / covered;
  e.rgb = glm::vec3(mean);
  double variance = 0.0;
  for (int v = 0; v < kViews; ++v) {
    if (sums[v].w <= 0.0f) continue;
    glm::dvec3 d = glm::dvec3(sums[v]) / double(sums[v].w) - mean;
    variance += sums[v].w * glm::dot(d, d) / 3.0;
  }
  e.viewVariance = float(variance / covered);
  e.bakerVersion = kBakerVersion;
  return e;
}

uint32_t AlbedoBaker::bakeSlot(AlbedoKey key) { return uint32_t(key % maxBatch()); }

uint32_t AlbedoBaker::maxBatch() { return shared::kAlbedoAtlasTiles * shared::kAlbedoAtlasTiles / kViews; }

AlbedoBaker::AlbedoBaker(gpu::Device& device, const scene::Scene& scene, scene::GpuScene& gpuScene,
                         const BakeSettings& settings)
    : device_(device), scene_(scene), gpuScene_(gpuScene), settings_(settings), executor_(device) {}

namespace {
// The bake's raster shaders and state; its layout, formats and scene table come from the pass.
gpu::GraphicsPipelineDesc bakePipeline() {
  gpu::GraphicsPipelineDesc r;
  r.name = "albedo.bake.raster";
  r.vertexShader = "albedo/bake.vert";
  r.fragmentShader = "albedo/bake.frag";
  r.vertexBindings = scene::GpuScene::vertexBindings();
  r.vertexAttributes = scene::GpuScene::vertexAttributes();
  r.cullMode = VK_CULL_MODE_NONE;  // a single-sided sheet still shows its colour from behind
  return r;
}
}  // namespace

std::vector<BakeOutcome> AlbedoBaker::bake(const std::vector<const Combination*>& batch) {
  if (batch.size() > maxBatch()) throw std::invalid_argument(fmt::format("albedo bake batch of {} > {}", batch.size(), maxBatch()));
  std::vector<BakeOutcome> outcomes(batch.size());
  if (batch.empty()) return outcomes;

  const uint32_t tile = settings_.tileSize, side = shared::kAlbedoAtlasTiles * tile;
  const uint32_t tiles = maxBatch() * kViews;
  std::vector<shared::AlbedoBakeDraw> draws;
  std::vector<uint32_t> drawTile, drawMesh;
  std::vector<bool> slotUsed(maxBatch(), false);
  for (const Combination* c : batch) {
    const uint32_t slot = bakeSlot(c->key);
    if (slotUsed[slot]) throw std::invalid_argument(fmt::format("albedo bake batch has two keys in slot {}", slot));
    slotUsed[slot] = true;
    const scene::Mesh& mesh = scene_.meshes.at(c->mesh);
    for (int v = 0; v < kViews; ++v) {
      shared::AlbedoBakeDraw d{};
      d.objectToClip = bakeViewProjection(mesh.bounds, v);
      d.material = std::min<uint32_t>(mesh.material, uint32_t(scene_.materials.size()) - 1);
      draws.push_back(d);
      drawTile.push_back(slot * kViews + v);
      drawMesh.push_back(c->mesh);
    }
  }

  graph::RenderGraph graph;
  gpuScene_.importBuffers(graph, executor_.nextFrame());

  // The bake runs outside a frame: the scene's table and buffers, no frame constants.
  lighting::RasterPass(device_, "albedo.bake.raster", bakePipeline())
      .colorOut(kBakeAtlas,
                graph::ResourceDesc::image2D(VK_FORMAT_R32G32B32A32_SFLOAT, side, side,
                                             "hit albedo of 6 views per combination, a = covered"),
                glm::vec4(0.0f))
      .depthOut(kBakeDepth, graph::ResourceDesc::image2D(VK_FORMAT_D32_SFLOAT, side, side, "depth, reversed"), 0.0f)
      .sceneTable(gpuScene_.table())
      .reads(scene::kSceneVertices, graph::Usage::VertexOrIndex)
      .reads(scene::kSceneIndices, graph::Usage::VertexOrIndex)
      .reads(scene::kSceneMaterials, graph::Usage::StorageRead)
      .push(shared::AlbedoBakeDraw{})  // each draw pushes its own
      .draw([&](graph::PassContext& ctx, const lighting::RasterPass::Use&) {
        gpuScene_.bindGeometry(ctx.cmd);
        for (size_t i = 0; i < draws.size(); ++i) {
          const uint32_t t = drawTile[i];
          ctx.setViewport(t % shared::kAlbedoAtlasTiles * tile, t / shared::kAlbedoAtlasTiles * tile, tile, tile);
          ctx.pushConstants(draws[i]);
          gpuScene_.drawMesh(ctx.cmd, drawMesh[i]);
        }
      })
      .add(graph);
  lighting::ComputePass(device_, "albedo.bake.reduce", "albedo/reduce.comp")
      .storageIn(shared::kAlbedoBindingAtlas, kBakeAtlas)
      .bufferOut(shared::kAlbedoBindingSums, kBakeSums,
                 graph::ResourceDesc::buffer(tiles * sizeof(shared::AlbedoTileSum), "per tile: albedo sum, covered pixels"))
      .push(shared::AlbedoReduceParams{tile, tiles, 0, 0})
      .dispatch(tiles, 1, 1, 1, 1, 1)
      .add(graph);
  graph.markOutput(kBakeSums);
  executor_.requestReadback(kBakeSums);
  if (keepAtlas_) executor_.requestReadback(kBakeAtlas);
  executor_.execute(graph, executor_.compile(graph));

  const graph::Readback& back = executor_.readback(kBakeSums);
  const auto* sums = reinterpret_cast<const shared::AlbedoTileSum*>(back.bytes.data());
  for (uint32_t c = 0; c < batch.size(); ++c) {
    std::array<glm::vec4, kViews> views{};
    for (int v = 0; v < kViews; ++v) views[v] = sums[bakeSlot(batch[c]->key) * kViews + v].sum;
    outcomes[c].key = batch[c]->key;
    outcomes[c].entry = entryFromViewSums(batch[c]->key, views, tile);
    if (outcomes[c].entry) outcomes[c].entry->label = batch[c]->label;
    else outcomes[c].error = "nothing visible from any direction (empty mesh or fully cut out)", outcomes[c].invisible = true;
  }
  return outcomes;
}

const graph::Readback* AlbedoBaker::lastAtlas() const {
  auto it = executor_.readbacks().find(std::string(kBakeAtlas));
  return it == executor_.readbacks().end() ? nullptr : &it->second;
}

}  // namespace tl::albedo
