#include "lighting/rt/rt_scene.h"

#include "lighting/common/emitter_table.h"

#include "scene/material_average.h"

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

RtScene::RtScene(gpu::Device& device, const scene::Scene& scene, scene::GpuScene& gpuScene, float simplifyRatio,
                 float simplifyError)
    : topLevel_(device, "rt.tlas"), ratio_(std::clamp(simplifyRatio, 0.01f, 1.0f)), device_(&device) {
  auto start = std::chrono::steady_clock::now();
  const auto& ranges = gpuScene.meshRanges();
  const VkDeviceAddress vertices = gpuScene.vertexBuffer().address();
  // Largest uniform scale any instance applies to a mesh: deviations are in object units.
  std::vector<float> meshScale(scene.meshes.size(), 0.0f);
  for (const auto& inst : scene.instances) {
    glm::dmat3 m(inst.transform);
    double s = std::max({glm::length(m[0]), glm::length(m[1]), glm::length(m[2])});
    meshScale[inst.mesh] = std::max(meshScale[inst.mesh], float(s));
  }
  meshInstance_.assign(scene.meshes.size(), -1);
  for (size_t i = 0; i < scene.instances.size(); ++i)
    if (scene.meshes[scene.instances[i].mesh].deforms()) meshInstance_[scene.instances[i].mesh] = int64_t(i);
  VkDeviceSize deformingBytes = 0;
  std::vector<VkDeviceSize> deformingOffset(scene.meshes.size(), 0);
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    const auto& mesh = scene.meshes[i];
    float deviation = 0.0f;
    // A deforming mesh keeps all its triangles: simplification judged on the rest pose (flat,
    // for cloth) would not hold once it moves.
    const bool deforms = mesh.deforms();
    // A cut-out keeps its triangles too: its outline is in the texture, which simplification
    // (judged on positions) would stretch over the holes.
    const bool alphaTested = gpuScene.meshAlphaTested(uint32_t(i));
    std::vector<uint32_t> indices = simplifyForRayTracing(mesh.vertices, mesh.indices,
                                                          deforms || alphaTested ? 1.0f : ratio_, simplifyError, &deviation);
    stats_.sourceTriangles += mesh.indices.size() / 3;
    stats_.rtTriangles += indices.size() / 3;
    stats_.maxDeviation = std::max(stats_.maxDeviation, deviation * meshScale[i]);
    gpu::Buffer ib(device, std::max<size_t>(1, indices.size()) * sizeof(uint32_t),
                   VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                   gpu::MemoryUsage::GpuOnly, fmt::format("rt.blasIndices.{}", i));
    if (!indices.empty()) gpu::uploadBuffer(device, ib, indices.data(), indices.size() * sizeof(uint32_t));
    gpu::TriangleGeometry g;
    g.vertices = vertices + VkDeviceAddress(ranges[i].vertexOffset) * sizeof(scene::Vertex);
    g.vertexStride = sizeof(scene::Vertex);
    g.vertexCount = ranges[i].vertexCount;
    g.indices = ib.address();
    g.triangleCount = uint32_t(indices.size() / 3);
    g.opaque = !alphaTested;  // only alpha-tested (MASK, BLEND) geometry runs the any-hit shader
    geometry_.push_back(g);
    if (deforms) {
      // Built below, into the shared storage, once its size is known.
      deformingOffset[i] = deformingBytes;
      deformingBytes += gpu::bottomLevelBytes(device, g, true);
      blas_.emplace_back();
      refitScratchOffset_.push_back(refitScratchBytes_);
      refitScratchBytes_ += gpu::refitScratchBytes(device, g);
      ++stats_.deformingMeshes;
    } else {
      blas_.push_back(gpu::buildBottomLevel(device, g, fmt::format("rt.blas.{}", i), true));
      stats_.blasBytes += blas_.back().bytes();
      refitScratchOffset_.push_back(0);
    }
    rtIndices_.push_back(std::move(ib));
    glm::vec3 lo(mesh.bounds.min), hi(mesh.bounds.max);
    meshCentre_.push_back(mesh.bounds.valid() ? (lo + hi) * 0.5f : glm::vec3(0.0f));
    meshRadius_.push_back(mesh.bounds.valid() ? glm::length(hi - lo) * 0.5f : 0.0f);
  }
  if (deformingBytes > 0) {
    deformingStorage_ = gpu::Buffer(device, deformingBytes,
                                    VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                    gpu::MemoryUsage::GpuOnly, "rt.blas.deforming");
    for (size_t i = 0; i < scene.meshes.size(); ++i)
      if (scene.meshes[i].deforms())
        blas_[i] = gpu::buildBottomLevelAt(device, geometry_[i], fmt::format("rt.blas.{}", i), deformingStorage_,
                                           deformingOffset[i], true);
    stats_.deformingBytes = deformingBytes;
    stats_.blasBytes += deformingBytes;
  }
  refitVersion_.assign(scene.meshes.size(), 0);
  for (size_t i = 0; i < scene.meshes.size(); ++i) refitVersion_[i] = gpuScene.meshVersion(uint32_t(i));
  stats_.blasBuildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

  // Once per material (texture averages touch every texel), then per instance. The albedo
  // is the texture-average fallback until setInstanceAlbedo() gives the resolved one.
  std::vector<glm::vec4> albedo, emission;
  std::vector<glm::vec3> modeAlbedo[3];
  for (const auto& m : scene.materials) {
    albedo.push_back(glm::vec4(scene::materialAverageAlbedo(scene, m), 0.0f));
    emission.push_back(glm::vec4(scene::materialAverageEmission(scene, m), 0.0f));
    for (uint32_t mode = 0; mode < 3; ++mode) modeAlbedo[mode].push_back(scene::materialAverageAlbedo(scene, m, mode));
  }
  std::vector<shared::RtInstance>& data = instances_;
  data.assign(std::max<size_t>(1, scene.instances.size()), shared::RtInstance{});
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const uint32_t mesh = scene.instances[i].mesh;
    data[i].albedo = albedo[scene.meshes[mesh].material];
    data[i].albedoScale = glm::vec4(1.0f);
    data[i].emission = emission[scene.meshes[mesh].material];
    data[i].material = scene.meshes[mesh].material;
    const VkDeviceAddress ia = rtIndices_[mesh].address();
    const VkDeviceAddress va = vertices + VkDeviceAddress(ranges[mesh].vertexOffset) * sizeof(scene::Vertex);
    data[i].indexAddress = glm::uvec2(uint32_t(ia), uint32_t(ia >> 32));
    data[i].vertexAddress = glm::uvec2(uint32_t(va), uint32_t(va >> 32));
  }
  for (uint32_t mode = 0; mode < 3; ++mode)
    for (size_t i = 0; i < scene.instances.size(); ++i)
      fallbackAlbedo_[mode].push_back(modeAlbedo[mode][scene.meshes[scene.instances[i].mesh].material]);
  instanceData_ = gpu::UploadRing(device, data.size() * sizeof(data[0]), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "rt.instanceData");
  instanceData_.write(0, data.data(), data.size() * sizeof(data[0]));  // new copies: no frame uses them yet

  std::vector<glm::vec3> instanceEmission;
  for (size_t i = 0; i < scene.instances.size(); ++i) instanceEmission.push_back(glm::vec3(data[i].emission));
  std::vector<shared::Emitter> emitters = buildEmitterTable(scene, instanceEmission).entries;
  emitterCount_ = uint32_t(emitters.size());
  for (const shared::Emitter& e : emitters)
    maxEmitterRadiance_ = std::max({maxEmitterRadiance_, e.radiance.x, e.radiance.y, e.radiance.z});
  if (emitters.empty()) emitters.push_back(shared::Emitter{});  // a binding needs a buffer
  emitterData_ = gpu::Buffer(device, emitters.size() * sizeof(emitters[0]), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                             gpu::MemoryUsage::Upload, "rt.emitters");
  emitterData_.write(emitters.data(), emitters.size() * sizeof(emitters[0]));
}

void RtScene::setInstanceAlbedo(const std::vector<glm::vec4>* resolved, uint32_t materials, uint64_t frame) {
  const std::vector<glm::vec3>& fallback = fallbackAlbedo_[std::min(materials, 2u)];
  for (size_t i = 0; i < fallback.size(); ++i) {
    const bool authored = materials == shared::kMaterialsAuthored && resolved && i < resolved->size();
    const glm::vec3 albedo = authored ? glm::vec3((*resolved)[i]) : fallback[i];
    instances_[i].albedo = glm::vec4(albedo, 0.0f);
    // Pre-traced hits read the G-buffer, which already shows the mode: only an override or a
    // database entry re-colours them.
    instances_[i].albedoScale = glm::vec4(albedo / glm::max(fallback[i], glm::vec3(1e-4f)), 0.0f);
  }
  instanceData_.write(frame, instances_.data(), instances_.size() * sizeof(instances_[0]));
}

void RtScene::prepareTopLevel(const scene::GpuScene& gpuScene, const RtCulling& culling, uint64_t frame,
                               const RefitPolicy& refits) {
  const auto& transforms = gpuScene.relativeTransforms();
  std::vector<glm::vec3> centres(transforms.size());
  std::vector<float> radii(transforms.size());
  for (size_t i = 0; i < transforms.size(); ++i) {
    uint32_t mesh = gpuScene.instanceMesh(i);
    const glm::mat4& t = transforms[i];
    float scale = std::max({glm::length(glm::vec3(t[0])), glm::length(glm::vec3(t[1])), glm::length(glm::vec3(t[2]))});
    centres[i] = glm::vec3(t * glm::vec4(meshCentre_[mesh], 1.0f));
    radii[i] = meshRadius_[mesh] * scale;
  }
  std::vector<gpu::TlasInstance> instances;
  const std::vector<uint32_t> kept = cullInstances(centres, radii, culling);
  for (uint32_t i : kept) instances.push_back({transforms[i], i, 0xFF, blas_[gpuScene.instanceMesh(i)].address()});
  topLevel_.prepare(instances, frame);

  // Deforming meshes whose vertices moved since their last refit: the throttle picks some.
  pendingRefits_.clear();
  stats_.staleLastFrame = stats_.refitsLastFrame = 0;
  stats_.refitVerticesLastFrame = 0;
  if (!hasDeforming()) return;
  std::vector<bool> inTopLevel(transforms.size(), false);
  for (uint32_t i : kept) inTopLevel[i] = true;
  std::vector<RefitCandidate> stale;
  for (uint32_t m = 0; m < meshInstance_.size(); ++m) {
    if (meshInstance_[m] < 0 || gpuScene.meshVersion(m) == refitVersion_[m]) continue;
    const size_t i = size_t(meshInstance_[m]);
    stale.push_back({m, geometry_[m].vertexCount, inTopLevel[i], radii[i] / std::max(glm::length(centres[i]), radii[i])});
  }
  stats_.staleLastFrame = uint32_t(stale.size());
  for (uint32_t m : scheduler_.choose(stale, refits, frame_++)) {
    pendingRefits_.push_back({m, gpuScene.meshVersion(m)});
    stats_.refitVerticesLastFrame += geometry_[m].vertexCount;
  }
  stats_.refitsLastFrame = uint32_t(pendingRefits_.size());
}

void RtScene::recordRefits(VkCommandBuffer cmd, const gpu::Buffer& scratch) {
  // Each refit of the frame has its own range of the scratch buffer: they run together.
  for (const auto& [mesh, version] : pendingRefits_) {
    gpu::recordRefit(cmd, *device_, blas_[mesh], geometry_[mesh], scratch, refitScratchOffset_[mesh]);
    refitVersion_[mesh] = version;
  }
  pendingRefits_.clear();
}

}  // namespace tl::lighting
