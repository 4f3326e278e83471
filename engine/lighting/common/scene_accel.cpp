#include "lighting/common/scene_accel.h"

#include "gpu/check.h"
#include "lighting/common/pass_builders.h"

#include <fmt/format.h>
#include <meshoptimizer.h>

#include <algorithm>
#include <chrono>
#include <numeric>

namespace tl::lighting {
namespace {

// Interleaves the low 10 bits of x, y, z (Morton order for the top level's instances).
uint32_t morton3(uint32_t x, uint32_t y, uint32_t z) {
  auto spread = [](uint32_t v) {
    v &= 0x3FF;
    v = (v | (v << 16)) & 0x030000FF;
    v = (v | (v << 8)) & 0x0300F00F;
    v = (v | (v << 4)) & 0x030C30C3;
    v = (v | (v << 2)) & 0x09249249;
    return v;
  };
  return spread(x) | (spread(y) << 1) | (spread(z) << 2);
}

size_t index(AccelDetail detail) { return detail == AccelDetail::Simplified ? 0 : 1; }

}  // namespace

std::vector<uint32_t> simplifyForRayTracing(const std::vector<scene::Vertex>& vertices,
                                            const std::vector<uint32_t>& indices, float ratio, float maxError,
                                            float* deviation) {
  const float* positions = &vertices[0].position.x;
  std::vector<uint32_t> reduced = indices;
  float error = 0.0f;
  if (ratio < 1.0f && indices.size() > 3) {
    size_t target = std::max<size_t>(3, size_t(double(indices.size() / 3) * ratio) * 3);
    reduced.resize(indices.size());
    size_t count = meshopt_simplify(reduced.data(), indices.data(), indices.size(), positions, vertices.size(),
                                    sizeof(scene::Vertex), target, maxError, 0, &error);
    reduced.resize(count);
    error *= meshopt_simplifyScale(positions, vertices.size(), sizeof(scene::Vertex));
    if (reduced.empty()) reduced = indices, error = 0.0f;  // never lose a whole mesh
  }
  std::vector<uint32_t> sorted(reduced.size());
  if (!reduced.empty())
    meshopt_spatialSortTriangles(sorted.data(), reduced.data(), reduced.size(), positions, vertices.size(),
                                 sizeof(scene::Vertex));
  if (deviation) *deviation = error;
  return sorted;
}

std::vector<uint32_t> cullInstances(const std::vector<glm::vec3>& centres, const std::vector<float>& radii,
                                    const RtCulling& c) {
  // Frustum planes from the (camera-relative) view-projection, Gribb & Hartmann; reversed-Z
  // infinite projection: the far plane is at infinity, so five planes.
  const glm::mat4 m = glm::transpose(c.viewProj);
  glm::vec4 planes[5] = {m[3] + m[0], m[3] - m[0], m[3] + m[1], m[3] - m[1], m[3] - m[2]};
  for (auto& p : planes) p /= glm::length(glm::vec3(p));
  std::vector<uint32_t> kept;
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (uint32_t i = 0; i < centres.size(); ++i) {
    bool inside = true;
    for (const auto& p : planes) inside &= glm::dot(glm::vec3(p), centres[i]) + p.w >= -(radii[i] + c.margin);
    // The camera sits at the origin of camera-relative space.
    float distance = std::max(glm::length(centres[i]) - radii[i], 0.0f);
    bool contributes = distance <= 0.0f || radii[i] >= c.minAngle * distance;
    if (!inside || !contributes || distance > c.maxDistance) continue;
    kept.push_back(i);
    lo = glm::min(lo, centres[i]);
    hi = glm::max(hi, centres[i]);
  }
  // Morton order of the centres: lavapipe's builder splits the instance list in order.
  std::vector<uint32_t> code(kept.size());
  glm::vec3 scale = 1023.0f / glm::max(hi - lo, glm::vec3(1e-6f));
  for (size_t k = 0; k < kept.size(); ++k) {
    glm::uvec3 q(glm::clamp((centres[kept[k]] - lo) * scale, glm::vec3(0.0f), glm::vec3(1023.0f)));
    code[k] = morton3(q.x, q.y, q.z);
  }
  std::vector<size_t> order(kept.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return code[a] < code[b]; });
  std::vector<uint32_t> out(kept.size());
  for (size_t k = 0; k < kept.size(); ++k) out[k] = kept[order[k]];
  return out;
}

RtCulling simplifiedCulling(const FrameInputs& in) {
  const RenderSettings& s = in.settings;  // automatic values resolved (render_settings.h resolveAutomatic)
  RtCulling culling;
  culling.viewProj = in.constants.viewProj;
  culling.margin = s.rtCullMargin;  // resolved: the ray length unless set
  culling.minAngle = s.rtCullAngle;
  culling.maxDistance = s.rtBlendDistance + culling.margin;
  return culling;
}

// One level of detail: per mesh a bottom level (the deforming ones side by side in one buffer
// the graph knows by name), the top level, and what a frame updates.
struct SceneAccel::Level {
  AccelDetail detail;
  const AccelNames& names;
  // What it was built for.
  uint64_t sceneId = 0;
  float ratio = 1.0f, maxError = 0.0f;
  bool built = false;
  uint64_t generation = 0;

  std::vector<gpu::AccelerationStructure> blas;  // per mesh
  std::vector<gpu::Buffer> ownIndices;            // per mesh, simplified level: its reduced triangle list
  std::vector<VkDeviceAddress> meshIndices;       // per mesh: the triangle list its bottom level holds
  std::vector<gpu::TriangleGeometry> geometry;    // per mesh, as built
  std::vector<glm::vec3> meshCentre;              // object-space bounding sphere per mesh
  std::vector<float> meshRadius;
  std::vector<int64_t> meshInstance;              // per mesh: its one instance (deforming meshes), else -1
  std::vector<uint64_t> version;                  // per mesh: the vertex version its bottom level holds
  std::vector<VkDeviceSize> scratchOffset;        // per mesh: its range of the refit or rebuild scratch
  VkDeviceSize scratchBytes = 0;
  gpu::Buffer deformingStorage;
  gpu::TopLevelBuilder topLevel;
  std::vector<glm::mat4> topLevelTransforms;      // full level: what its top level was built from
  RefitScheduler scheduler;
  uint64_t refitFrame = 0;
  std::vector<std::pair<uint32_t, uint64_t>> pending;  // mesh, the version it will hold
  AccelStats stats;
  TraceStructures structures;

  Level(AccelDetail d, const AccelNames& n) : detail(d), names(n) {}

  bool stale(const FrameInputs& in) const {
    if (!built || sceneId != in.scene.id()) return true;
    return detail == AccelDetail::Simplified &&
           (ratio != std::clamp(in.settings.rtSimplifyRatio, 0.01f, 1.0f) || maxError != in.settings.rtSimplifyError);
  }

  void build(FrameInputs& in, uint64_t newGeneration);
  void addPasses(graph::RenderGraph& graph, FrameInputs& in);
  void addSimplifiedPasses(graph::RenderGraph& graph, FrameInputs& in);
  void addFullPasses(graph::RenderGraph& graph, FrameInputs& in);
};

void SceneAccel::Level::build(FrameInputs& in, uint64_t newGeneration) {
  in.device.waitIdle();  // frames in flight may still trace the structures replaced here
  const auto start = std::chrono::steady_clock::now();
  const scene::Scene& scene = in.sceneData;
  scene::GpuScene& gpuScene = in.scene;
  const bool simplified = detail == AccelDetail::Simplified;
  ratio = std::clamp(in.settings.rtSimplifyRatio, 0.01f, 1.0f);
  maxError = in.settings.rtSimplifyError;
  sceneId = gpuScene.id();
  generation = newGeneration;
  // The top level points into the old bottom levels: a new one even when the new scene's
  // transforms are the same (the same file loaded again).
  topLevel = gpu::TopLevelBuilder(in.device, names.tlas);
  topLevelTransforms.clear();
  blas.clear(), ownIndices.clear(), meshIndices.clear(), geometry.clear(), meshCentre.clear(), meshRadius.clear();
  scratchOffset.clear(), pending.clear(), version.clear();
  deformingStorage.reset();
  scratchBytes = 0;
  scheduler = RefitScheduler{};
  stats = AccelStats{};

  const auto& ranges = gpuScene.meshRanges();
  const VkDeviceAddress vertices = gpuScene.vertexBuffer().address();
  // Largest uniform scale any instance applies to a mesh: deviations are in object units.
  std::vector<float> meshScale(scene.meshes.size(), 0.0f);
  for (const auto& inst : scene.instances) {
    glm::dmat3 m(inst.transform);
    double s = std::max({glm::length(m[0]), glm::length(m[1]), glm::length(m[2])});
    meshScale[inst.mesh] = std::max(meshScale[inst.mesh], float(s));
  }
  meshInstance.assign(ranges.size(), -1);
  for (size_t i = 0; i < scene.instances.size(); ++i)
    if (scene.meshes[scene.instances[i].mesh].deforms()) meshInstance[scene.instances[i].mesh] = int64_t(i);
  VkDeviceSize deformingBytes = 0;
  std::vector<VkDeviceSize> placeAt(ranges.size(), 0);
  for (uint32_t i = 0; i < ranges.size(); ++i) {
    const bool deforms = i < scene.meshes.size() && scene.meshes[i].deforms();
    // A cut-out needs the any-hit shader; everything else stays opaque (no any-hit calls).
    const bool alphaTested = gpuScene.meshAlphaTested(i);
    gpu::TriangleGeometry g;
    g.vertices = vertices + VkDeviceAddress(ranges[i].vertexOffset) * sizeof(scene::Vertex);
    g.vertexStride = sizeof(scene::Vertex);
    g.vertexCount = ranges[i].vertexCount;
    g.opaque = !alphaTested;
    stats.sourceTriangles += ranges[i].indexCount / 3;
    if (simplified) {
      // A deforming mesh keeps all its triangles: simplification judged on the rest pose (flat,
      // for cloth) would not hold once it moves. A cut-out keeps its triangles too: its outline
      // is in the texture, which simplification (judged on positions) would stretch over the holes.
      const auto& mesh = scene.meshes[i];
      float deviation = 0.0f;
      std::vector<uint32_t> reduced = simplifyForRayTracing(mesh.vertices, mesh.indices,
                                                            deforms || alphaTested ? 1.0f : ratio, maxError, &deviation);
      stats.maxDeviation = std::max(stats.maxDeviation, deviation * meshScale[i]);
      gpu::Buffer ib(in.device, std::max<size_t>(1, reduced.size()) * sizeof(uint32_t),
                     VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                     gpu::MemoryUsage::GpuOnly, fmt::format("{}.indices.{}", names.tlas, i));
      if (!reduced.empty()) gpu::uploadBuffer(in.device, ib, reduced.data(), reduced.size() * sizeof(uint32_t));
      g.indices = ib.address();
      g.triangleCount = uint32_t(reduced.size() / 3);
      ownIndices.push_back(std::move(ib));
    } else {
      g.indices = gpuScene.indexBuffer().address() + VkDeviceAddress(ranges[i].firstIndex) * sizeof(uint32_t);
      g.triangleCount = ranges[i].indexCount / 3;
    }
    stats.triangles += g.triangleCount;
    geometry.push_back(g);
    meshIndices.push_back(g.indices);
    const std::string name = fmt::format("{}.blas.{}", simplified ? "accel.simplified" : "accel.full", i);
    if (deforms) {
      // Built below, into the shared storage, once its size is known: refittable (simplified)
      // or rebuilt in place (full).
      placeAt[i] = deformingBytes;
      deformingBytes += gpu::bottomLevelBytes(in.device, g, simplified);
      scratchOffset.push_back(scratchBytes);
      scratchBytes += simplified ? gpu::refitScratchBytes(in.device, g) : gpu::rebuildScratchBytes(in.device, g);
      blas.emplace_back();
      ++stats.deformingMeshes;
    } else {
      blas.push_back(gpu::buildBottomLevel(in.device, g, name, /*compact=*/simplified));
      stats.blasBytes += blas.back().bytes();
      scratchOffset.push_back(0);
    }
    const auto& b = i < scene.meshes.size() ? scene.meshes[i].bounds : scene::Bounds{};
    const glm::vec3 lo(b.min), hi(b.max);
    meshCentre.push_back(b.valid() ? (lo + hi) * 0.5f : glm::vec3(0.0f));
    meshRadius.push_back(b.valid() ? glm::length(hi - lo) * 0.5f : 0.0f);
    version.push_back(gpuScene.meshVersion(i));
  }
  if (deformingBytes > 0) {
    deformingStorage = gpu::Buffer(in.device, deformingBytes,
                                   VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                   gpu::MemoryUsage::GpuOnly, names.blasDeforming);
    for (uint32_t i = 0; i < ranges.size(); ++i)
      if (!blas[i])
        blas[i] = gpu::buildBottomLevelAt(in.device, geometry[i],
                                          fmt::format("{}.blas.{}", simplified ? "accel.simplified" : "accel.full", i),
                                          deformingStorage, placeAt[i], simplified);
    stats.deformingBytes = deformingBytes;
    stats.blasBytes += deformingBytes;
  }
  stats.meshes = uint32_t(ranges.size());
  stats.blasBuildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  built = true;
}

void SceneAccel::Level::addPasses(graph::RenderGraph& graph, FrameInputs& in) {
  stats.sceneInstances = uint32_t(in.scene.instanceCount());
  if (detail == AccelDetail::Simplified)
    addSimplifiedPasses(graph, in);
  else
    addFullPasses(graph, in);
  structures.tlas = topLevel.structure().handle();
  structures.names = {names.tlas};
  if (deformingStorage) structures.names.push_back(names.blasDeforming);
  stats.instancesInTopLevel = topLevel.instanceCount();
}

// The culled top level, rebuilt every frame; deforming meshes whose vertices moved since their
// last refit are refitted as the throttle picks them (RefitScheduler).
void SceneAccel::Level::addSimplifiedPasses(graph::RenderGraph& graph, FrameInputs& in) {
  const scene::GpuScene& gpuScene = in.scene;
  const auto& transforms = gpuScene.relativeTransforms();
  std::vector<glm::vec3> centres(transforms.size());
  std::vector<float> radii(transforms.size());
  for (size_t i = 0; i < transforms.size(); ++i) {
    const uint32_t mesh = gpuScene.instanceMesh(i);
    const glm::mat4& t = transforms[i];
    const float scale = std::max({glm::length(glm::vec3(t[0])), glm::length(glm::vec3(t[1])), glm::length(glm::vec3(t[2]))});
    centres[i] = glm::vec3(t * glm::vec4(meshCentre[mesh], 1.0f));
    radii[i] = meshRadius[mesh] * scale;
  }
  const std::vector<uint32_t> kept = cullInstances(centres, radii, simplifiedCulling(in));
  std::vector<gpu::TlasInstance> instances;
  for (uint32_t i : kept) instances.push_back({transforms[i], i, 0xFF, blas[gpuScene.instanceMesh(i)].address()});
  topLevel.prepare(instances, in.frame);

  pending.clear();
  stats.staleLastFrame = stats.refitsLastFrame = 0;
  stats.refitVerticesLastFrame = 0;
  if (deformingStorage) {
    std::vector<bool> inTopLevel(transforms.size(), false);
    for (uint32_t i : kept) inTopLevel[i] = true;
    std::vector<RefitCandidate> stale;
    for (uint32_t m = 0; m < meshInstance.size(); ++m) {
      if (meshInstance[m] < 0 || gpuScene.meshVersion(m) == version[m]) continue;
      const size_t i = size_t(meshInstance[m]);
      stale.push_back({m, geometry[m].vertexCount, inTopLevel[i], radii[i] / std::max(glm::length(centres[i]), radii[i])});
    }
    stats.staleLastFrame = uint32_t(stale.size());
    RefitPolicy policy;
    policy.top = in.settings.rtRefitTop;
    policy.random = in.settings.rtRefitRandom;
    policy.vertexBudget = in.settings.rtRefitVertexBudget;
    for (uint32_t m : scheduler.choose(stale, policy, refitFrame++)) {
      pending.push_back({m, gpuScene.meshVersion(m)});
      stats.refitVerticesLastFrame += geometry[m].vertexCount;
    }
    stats.refitsLastFrame = uint32_t(pending.size());
  }

  graph.importBuffer(names.tlas, graph::ResourceDesc::buffer(topLevel.storage().size(),
                                                             "top-level acceleration structure, simplified meshes (culled instances)"),
                     topLevel.storage());
  graph.importBuffer(names.tlasInstances, graph::ResourceDesc::buffer(topLevel.instances().size(),
                                                                      "the simplified top level's instances (host-written)"),
                     topLevel.instances());
  if (deformingStorage)
    graph.importBuffer(names.blasDeforming,
                       graph::ResourceDesc::buffer(deformingStorage.size(),
                                                   "bottom levels of the deforming meshes (refitted under a throttle)"),
                       deformingStorage);
  if (!pending.empty())
    AccelerationStructurePass(names.updatePass)
        .input(scene::kSceneVertices)
        .reads(names.blasDeforming)  // an update reads the structure it rewrites
        .writes(names.blasDeforming)
        .scratch(names.blasScratch, scratchBytes, "scratch of the refits")
        .record([this](graph::PassContext& ctx, const gpu::Buffer& scratch) {
          // Each refit of the frame has its own range of the scratch buffer: they run together.
          for (const auto& [mesh, v] : pending) {
            gpu::recordRefit(ctx.cmd, ctx.device, blas[mesh], geometry[mesh], scratch, scratchOffset[mesh]);
            version[mesh] = v;
          }
          pending.clear();
        })
        .add(graph);
  AccelerationStructurePass tlas(names.tlasPass);
  tlas.input(names.tlasInstances);
  if (deformingStorage) tlas.reads(names.blasDeforming);
  tlas.writes(names.tlas)
      .scratch(names.tlasScratch, topLevel.scratchBytes(), "scratch of the top-level build")
      .record([this](graph::PassContext& ctx, const gpu::Buffer& scratch) { topLevel.record(ctx.cmd, scratch); })
      .add(graph);
}

// Every instance; deforming meshes that moved are rebuilt exactly (no throttle, no refit). The
// top level is camera-relative like everything the GPU sees, so it follows the camera: it is
// rebuilt when a transform or a bottom level changed.
void SceneAccel::Level::addFullPasses(graph::RenderGraph& graph, FrameInputs& in) {
  const scene::GpuScene& gpuScene = in.scene;
  pending.clear();
  for (uint32_t m = 0; m < version.size(); ++m)
    if (gpuScene.meshVersion(m) != version[m]) pending.push_back({m, gpuScene.meshVersion(m)});
  stats.staleLastFrame = stats.refitsLastFrame = uint32_t(pending.size());
  stats.refitVerticesLastFrame = 0;
  for (const auto& p : pending) stats.refitVerticesLastFrame += geometry[p.first].vertexCount;

  const auto& transforms = gpuScene.relativeTransforms();
  const bool rebuildTop = !topLevel || transforms != topLevelTransforms || !pending.empty();
  if (rebuildTop) {
    std::vector<gpu::TlasInstance> instances;
    for (size_t i = 0; i < transforms.size(); ++i)
      instances.push_back({transforms[i], uint32_t(i), 0xFF, blas[gpuScene.instanceMesh(i)].address()});
    topLevel.prepare(instances, in.frame);
    topLevelTransforms = transforms;
  }
  graph.importBuffer(names.tlas, graph::ResourceDesc::buffer(topLevel.storage().size(),
                                                             "top-level acceleration structure, every triangle and instance"),
                     topLevel.storage());
  graph.importBuffer(names.tlasInstances, graph::ResourceDesc::buffer(topLevel.instances().size(),
                                                                      "the full top level's instances (host-written)"),
                     topLevel.instances());
  if (deformingStorage)
    graph.importBuffer(names.blasDeforming, graph::ResourceDesc::buffer(deformingStorage.size(),
                                                                        "bottom levels of the deforming meshes (rebuilt exactly)"),
                       deformingStorage);
  if (!pending.empty())
    AccelerationStructurePass(names.updatePass)
        .input(scene::kSceneVertices)
        .input(scene::kSceneIndices)
        .writes(names.blasDeforming)
        .scratch(names.blasScratch, scratchBytes, "scratch of the rebuilds")
        .record([this](graph::PassContext& ctx, const gpu::Buffer& scratch) {
          for (const auto& [mesh, v] : pending) {
            gpu::recordRebuild(ctx.cmd, ctx.device, blas[mesh], geometry[mesh], scratch, scratchOffset[mesh]);
            version[mesh] = v;
          }
          pending.clear();
        })
        .add(graph);
  if (rebuildTop) {
    AccelerationStructurePass top(names.tlasPass);
    top.input(names.tlasInstances);
    if (deformingStorage) top.reads(names.blasDeforming);
    top.writes(names.tlas)
        .scratch(names.tlasScratch, topLevel.scratchBytes(), "scratch of the top-level build")
        .record([this](graph::PassContext& ctx, const gpu::Buffer& scratch) { topLevel.record(ctx.cmd, scratch); })
        .add(graph);
  }
}

SceneAccel::SceneAccel() {
  levels_[0] = std::make_unique<Level>(AccelDetail::Simplified, kAccelSimplified);
  levels_[1] = std::make_unique<Level>(AccelDetail::Full, kAccelFull);
}

SceneAccel::~SceneAccel() = default;

const TraceStructures& SceneAccel::addPasses(graph::RenderGraph& graph, FrameInputs& in, AccelDetail detail) {
  Level& level = *levels_[index(detail)];
  // Another tracer of this frame asked first: its passes are in the graph already.
  if (level.built && !level.stale(in) && graph.find(level.names.tlas)) return level.structures;
  if (level.stale(in)) level.build(in, ++generations_);
  level.addPasses(graph, in);
  return level.structures;
}

const AccelStats& SceneAccel::stats(AccelDetail detail) const { return levels_[index(detail)]->stats; }

const std::vector<VkDeviceAddress>& SceneAccel::meshIndices(AccelDetail detail) const {
  return levels_[index(detail)]->meshIndices;
}

const TraceStructures& traceStructures(graph::RenderGraph& graph, FrameInputs& in, AccelDetail detail) {
  TL_CHECK(in.accel != nullptr, "a tracer asked for the scene's acceleration structures in a frame without a SceneAccel");
  return in.accel->addPasses(graph, in, detail);
}

uint64_t SceneAccel::generation(AccelDetail detail) const { return levels_[index(detail)]->generation; }

}  // namespace tl::lighting
