#include "scene/gpu_scene.h"

#include <algorithm>

#include "gpu/check.h"
#include "gpu/formats.h"
#include "shared/scene.h"

#include <fmt/format.h>

#include <atomic>
#include <cmath>

namespace tl::scene {

using shared::GpuInstance;
using shared::GpuMaterial;

VkFormat textureFormat(const Texture& t) {
  switch (t.format) {
    case TexelFormat::Rgba16Unorm: return VK_FORMAT_R16G16B16A16_UNORM;
    case TexelFormat::Rgba16Float: return VK_FORMAT_R16G16B16A16_SFLOAT;
    case TexelFormat::Rgba8: break;
  }
  return t.srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
}

std::vector<VkVertexInputBindingDescription> GpuScene::vertexBindings() {
  return {{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX}};
}

std::vector<VkVertexInputAttributeDescription> GpuScene::vertexAttributes() {
  return {{shared::kAttrPosition, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
          {shared::kAttrNormal, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)},
          {shared::kAttrTangent, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, tangent)},
          {shared::kAttrUv, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)},
          {shared::kAttrUv1, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv1)},
          {shared::kAttrColor, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, color)}};
}

namespace {

static_assert(offsetof(Vertex, uv) == shared::kVertexUv * sizeof(float));
static_assert(offsetof(Vertex, uv1) == shared::kVertexUv1 * sizeof(float));
static_assert(offsetof(Vertex, color) == shared::kVertexColor * sizeof(float));
static_assert(sizeof(Vertex) == shared::kVertexFloats * sizeof(float));

VkSamplerAddressMode addressMode(Wrap w) {
  switch (w) {
    case Wrap::ClampToEdge: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    case Wrap::MirroredRepeat: return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    case Wrap::Repeat: break;
  }
  return VK_SAMPLER_ADDRESS_MODE_REPEAT;
}

// A glTF sampler as Vulkan's. Linear minification keeps 8x anisotropy (the default sampler's);
// a nearest one does not (it would blur what the file asked to keep sharp).
VkSamplerCreateInfo samplerInfo(gpu::Device& device, const SamplerMode& m) {
  VkSamplerCreateInfo ci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  ci.magFilter = m.magNearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR;
  ci.minFilter = m.minNearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR;
  ci.mipmapMode = m.mipNearest || m.noMipmaps ? VK_SAMPLER_MIPMAP_MODE_NEAREST : VK_SAMPLER_MIPMAP_MODE_LINEAR;
  ci.addressModeU = addressMode(m.wrapS);
  ci.addressModeV = addressMode(m.wrapT);
  ci.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  ci.maxLod = m.noMipmaps ? 0.0f : VK_LOD_CLAMP_NONE;
  ci.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
  if (!m.minNearest && !m.magNearest) {
    ci.anisotropyEnable = VK_TRUE;
    ci.maxAnisotropy = std::min(8.0f, device.limits().maxSamplerAnisotropy);
  }
  return ci;
}

uint32_t alphaModeOnGpu(AlphaMode mode) {
  switch (mode) {
    case AlphaMode::Mask: return shared::kAlphaMask;
    case AlphaMode::Blend: return shared::kAlphaBlend;
    case AlphaMode::Opaque: break;
  }
  return shared::kAlphaOpaque;
}

// KHR_materials_volume's Beer-Lambert coefficient per scene unit: attenuationColor is what is
// left after attenuationDistance. A colour of 0 absorbs everything within a hair's breadth of
// the surface, kept finite (1e-6 left per distance) so exp(-sigma t) stays a number.
glm::vec3 volumeAbsorption(const Material& m) {
  if (!(m.thickness > 0.0f) || !std::isfinite(m.attenuationDistance)) return glm::vec3(0.0f);
  return -glm::log(glm::max(m.attenuationColor, glm::vec3(1e-6f))) / m.attenuationDistance;
}

shared::GpuTextureSlot textureSlot(const std::optional<TextureRef>& r) {
  shared::GpuTextureSlot s{};
  s.linear = glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
  s.texture = shared::kNoTexture;
  if (!r) return s;
  // KHR_texture_transform: uv' = offset + R S uv with R's columns (cos, -sin) and (sin, cos);
  // the extension's example (offset (0, 1), rotation pi/2, scale 0.5 shows the lower-left
  // quadrant) fixes the sense of rotation.
  const float c = std::cos(r->rotation), sn = std::sin(r->rotation);
  s.linear = glm::vec4(c * r->scale.x, -sn * r->scale.x, sn * r->scale.y, c * r->scale.y);
  s.offset = r->offset;
  s.texture = r->texture;
  s.texCoord = r->texCoord;
  return s;
}

}  // namespace

GpuScene::GpuScene(gpu::Device& device, const Scene& scene) : device_(device), drawArena_(device) {
  static std::atomic<uint64_t> nextId{1};
  id_ = nextId++;
  // Geometry: all meshes in one vertex and one index buffer.
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;
  for (const Mesh& m : scene.meshes) {
    meshes_.push_back({uint32_t(indices.size()), uint32_t(m.indices.size()), int32_t(vertices.size()),
                       uint32_t(m.vertices.size()), m.material});
    vertices.insert(vertices.end(), m.vertices.begin(), m.vertices.end());
    indices.insert(indices.end(), m.indices.begin(), m.indices.end());
  }
  meshVersions_.assign(meshes_.size(), 0);
  // Acceleration-structure builds read the same buffers (only where the extension exists).
  VkBufferUsageFlags geometryUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  if (device.rayTracing().pipeline) geometryUsage |= VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR;
  vertices_ = gpu::Buffer(device, vertices.size() * sizeof(Vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | geometryUsage,
                          gpu::MemoryUsage::GpuOnly, "scene.vertices");
  indices_ = gpu::Buffer(device, indices.size() * sizeof(uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT | geometryUsage,
                         gpu::MemoryUsage::GpuOnly, "scene.indices");
  gpu::uploadBuffer(device, vertices_, vertices.data(), vertices.size() * sizeof(Vertex));
  gpu::uploadBuffer(device, indices_, indices.data(), indices.size() * sizeof(uint32_t));

  // Deforming meshes' last-frame positions for the motion vectors, starting at rest (no motion);
  // a scene that does not deform has none.
  previousOffset_.assign(scene.meshes.size(), shared::kNoPreviousPositions);
  uploadedPositions_.resize(scene.meshes.size());
  std::vector<glm::vec4> previous;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    if (!scene.meshes[m].deforms()) continue;
    previousOffset_[m] = uint32_t(previous.size());
    for (const Vertex& v : scene.meshes[m].vertices) uploadedPositions_[m].emplace_back(v.position, 1.0f);
    previous.insert(previous.end(), uploadedPositions_[m].begin(), uploadedPositions_[m].end());
  }
  if (!previous.empty()) {
    previousPositions_ = gpu::Buffer(device, previous.size() * sizeof(glm::vec4),
                                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                     gpu::MemoryUsage::GpuOnly, kScenePreviousPositions);
    gpu::uploadBuffer(device, previousPositions_, previous.data(), previous.size() * sizeof(glm::vec4));
  }

  // Textures with full mip chains in the precision they were stored in (scene.h TexelFormat);
  // 8-bit sRGB-ness comes from how the material uses them.
  for (const Texture& t : scene.textures) {
    gpu::ImageInfo info{textureFormat(t), {t.width, t.height, 1}, gpu::mipCount(t.width, t.height),
                        VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT};
    gpu::Image img(device, info, fmt::format("scene.texture.{}", t.name));
    if (t.format == TexelFormat::Rgba8)
      gpu::uploadImage2DWithMips(device, img, t.rgba8.data(), t.rgba8.size());
    else
      gpu::uploadImage2DWithMips(device, img, t.rgba16.data(), t.rgba16.size() * sizeof(uint16_t));
    textures_.push_back(std::move(img));
  }
  TL_CHECK(textures_.size() <= shared::kSceneMaxTextures, "scene {} has {} textures; at most {} are supported",
           scene.name, textures_.size(), shared::kSceneMaxTextures);
  // One Vulkan sampler per distinct glTF sampler mode (textures sharing a mode share it).
  std::vector<VkSampler> textureSamplers;
  for (const Texture& t : scene.textures) {
    size_t k = 0;
    while (k < samplerModes_.size() && !(samplerModes_[k] == t.sampler)) ++k;
    if (k == samplerModes_.size()) {
      samplerModes_.push_back(t.sampler);
      samplers_.emplace_back(device, samplerInfo(device, t.sampler), fmt::format("scene.sampler{}", k));
    }
    textureSamplers.push_back(samplers_[k].handle());
  }

  // Materials.
  std::vector<GpuMaterial> materials;
  for (const Material& m : scene.materials) {
    GpuMaterial g{};
    g.baseColorFactor = m.baseColorFactor;
    g.emissive = glm::vec4(m.emissiveFactor * m.emissiveStrength, 0.0f);
    g.metallic = m.metallic;
    g.roughness = m.roughness;
    g.normalScale = m.normalScale;
    g.alphaCutoff = m.alphaCutoff;
    g.alphaMode = alphaModeOnGpu(m.alphaMode);
    g.occlusionStrength = m.occlusionStrength;
    g.flags = (m.doubleSided ? shared::kMaterialDoubleSided : 0u) | (m.unlit ? shared::kMaterialUnlit : 0u);
    g.ior = m.ior;
    g.specularColor = glm::vec4(m.specularColorFactor, m.specularFactor);
    g.specularTexture = textureSlot(m.specularTexture);
    g.specularColorTexture = textureSlot(m.specularColorTexture);
    g.baseColorTexture = textureSlot(m.baseColorTexture);
    g.normalTexture = textureSlot(m.normalTexture);
    g.metallicRoughnessTexture = textureSlot(m.metallicRoughnessTexture);
    g.emissiveTexture = textureSlot(m.emissiveTexture);
    g.occlusionTexture = textureSlot(m.occlusionTexture);
    g.transmission = m.transmits() ? m.transmission : 0.0f;
    g.transmissionTexture = textureSlot(m.transmissionTexture);
    g.thickness = m.thickness;
    g.absorption = glm::vec4(volumeAbsorption(m), 0.0f);
    g.clearcoat = m.unlit ? 0.0f : m.clearcoat;
    g.clearcoatRoughness = m.clearcoatRoughness;
    materials.push_back(g);
  }
  materials_ = gpu::Buffer(device, materials.size() * sizeof(GpuMaterial), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                           gpu::MemoryUsage::GpuOnly, "scene.materials");
  gpu::uploadBuffer(device, materials_, materials.data(), materials.size() * sizeof(GpuMaterial));

  for (const Instance& inst : scene.instances) drawMesh_.push_back(inst.mesh);
  meshAlphaTested_.assign(scene.meshes.size(), 0);
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Material& material = scene.materials[scene.meshes[m].material];
    meshAlphaTested_[m] = material.alphaMode != AlphaMode::Opaque || material.transmits();
  }
  for (uint32_t i = 0; i < drawMesh_.size(); ++i)
    (meshAlphaTested_[drawMesh_[i]] ? alphaTested_ : opaque_).push_back(i);
  const VkDeviceSize instanceBytes = std::max<size_t>(1, drawMesh_.size()) * sizeof(GpuInstance);
  instances_ = gpu::Buffer(device, instanceBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                           gpu::MemoryUsage::GpuOnly, "scene.instances");
  instanceUploads_ = gpu::UploadRing(device, instanceBytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, kSceneInstanceUpload);

  table_ = gpu::DescriptorTable(device,
                                {{shared::kSceneBindingMaterials, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1},
                                 {shared::kSceneBindingInstances, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1},
                                 {shared::kSceneBindingTextures, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1}},
                                shared::kSceneMaxTextures, "scene.table");
  table_.writeBuffer(shared::kSceneBindingMaterials, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, materials_.handle());
  table_.writeBuffer(shared::kSceneBindingInstances, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, instances_.handle());
  std::vector<VkImageView> views;
  for (auto& t : textures_) views.push_back(t.view());
  table_.writeImages(shared::kSceneBindingTextures, views, textureSamplers);
}

void GpuScene::updateInstances(const Scene& scene, const glm::dvec3& camera, const glm::dvec3& previousCamera,
                               uint64_t frame) {
  std::vector<GpuInstance> out(scene.instances.size());
  relative_.resize(scene.instances.size());
  if (!havePrevious_ || previousTransforms_.size() != scene.instances.size()) {
    previousTransforms_.clear();
    for (auto& i : scene.instances) previousTransforms_.push_back(i.transform);
  }
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& inst = scene.instances[i];
    // Subtract the camera in double: what reaches float is small near the viewer.
    glm::dmat4 rel = inst.transform;
    rel[3] = glm::dvec4(glm::dvec3(inst.transform[3]) - camera, 1.0);
    glm::dmat4 prevRel = previousTransforms_[i];
    prevRel[3] = glm::dvec4(glm::dvec3(prevRel[3]) - camera, 1.0);
    GpuInstance g{};
    g.modelRelative = glm::mat4(rel);
    relative_[i] = g.modelRelative;
    g.prevModelRelative = glm::mat4(prevRel);
    g.normalMatrix = glm::mat4(glm::mat3(glm::transpose(glm::inverse(glm::dmat3(inst.transform)))));
    g.material = scene.meshes[inst.mesh].material;
    g.instanceId = uint32_t(i + 1);
    g.vertexOffset = uint32_t(meshes_[drawMesh_[i]].vertexOffset);
    g.previousPositionOffset = previousOffset_[drawMesh_[i]];
    out[i] = g;
    previousTransforms_[i] = inst.transform;
  }
  (void)previousCamera;  // the previous camera enters through FrameConstants::prevViewProj
  havePrevious_ = true;
  if (!out.empty()) instanceUploads_.write(frame, out.data(), out.size() * sizeof(GpuInstance));
  uploadFrame_ = frame;
}

void GpuScene::importBuffers(graph::RenderGraph& graph, uint64_t frame) {
  auto imported = [&](graph::BufferName name, gpu::Buffer& b, const char* what) {
    graph.importBuffer(name, graph::ResourceDesc::buffer(b.size(), what), b);
  };
  imported(kSceneVertices, vertices_, "all meshes' vertices");
  imported(kSceneIndices, indices_, "all meshes' indices");
  imported(kSceneInstances, instances_, "camera-relative instance table");
  imported(kSceneMaterials, materials_, "material table");
  if (deforms()) imported(kScenePreviousPositions, previousPositions_, "deforming meshes' last-frame positions (motion vectors)");
  if (uploadFrame_ != frame) return;
  imported(kSceneInstanceUpload, instanceUploads_.forFrame(*uploadFrame_), "this frame's instance table, host-written");
  graph.addPass(
      "scene.instances.upload", graph::PassKind::Transfer,
      [](graph::PassBuilder& b) {
        b.read(kSceneInstanceUpload, graph::Usage::TransferSrc);
        b.write(kSceneInstances, graph::Usage::TransferDst);
      },
      [](graph::PassContext& ctx) {
        const gpu::Buffer& from = ctx.buffer(kSceneInstanceUpload);
        const VkBufferCopy region{0, 0, from.size()};
        vkCmdCopyBuffer(ctx.cmd, from.handle(), ctx.buffer(kSceneInstances).handle(), 1, &region);
      });
}

void GpuScene::bindGeometry(VkCommandBuffer cmd) const {
  VkDeviceSize offset = 0;
  VkBuffer vb = vertices_.handle();
  vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
  vkCmdBindIndexBuffer(cmd, indices_.handle(), 0, VK_INDEX_TYPE_UINT32);
}

void GpuScene::drawMesh(VkCommandBuffer cmd, uint32_t mesh) const {
  const MeshRange& m = meshes_.at(mesh);
  vkCmdDrawIndexed(cmd, m.indexCount, 1, m.firstIndex, m.vertexOffset, 0);
}

// Instance i's draw: its mesh's triangles, gl_InstanceIndex = i.
VkDrawIndexedIndirectCommand GpuScene::indexedDrawOf(uint32_t instance) const {
  const MeshRange& m = meshes_[drawMesh_[instance]];
  return {m.indexCount, 1, m.firstIndex, m.vertexOffset, instance};
}

void GpuScene::drawAll(graph::PassContext& ctx) const {
  bindGeometry(ctx.cmd);
  std::vector<VkDrawIndexedIndirectCommand> draws(drawMesh_.size());
  for (uint32_t i = 0; i < drawMesh_.size(); ++i) draws[i] = indexedDrawOf(i);
  drawArena_.drawIndexed(ctx.cmd, ctx.frameIndex, draws);
}

void GpuScene::drawInstances(graph::PassContext& ctx, const std::vector<uint32_t>& instances) const {
  bindGeometry(ctx.cmd);
  std::vector<VkDrawIndexedIndirectCommand> draws;
  draws.reserve(instances.size());
  for (uint32_t i : instances)
    if (i < drawMesh_.size()) draws.push_back(indexedDrawOf(i));
  drawArena_.drawIndexed(ctx.cmd, ctx.frameIndex, draws);
}

void GpuScene::drawInstancesUnindexed(graph::PassContext& ctx, const std::vector<uint32_t>& instances) const {
  // The same ranges without the index buffer: vertex k is the mesh's firstIndex + k.
  std::vector<VkDrawIndirectCommand> draws;
  draws.reserve(instances.size());
  for (uint32_t i : instances) {
    if (i >= drawMesh_.size()) continue;
    const VkDrawIndexedIndirectCommand d = indexedDrawOf(i);
    draws.push_back({d.indexCount, d.instanceCount, d.firstIndex, d.firstInstance});
  }
  drawArena_.draw(ctx.cmd, ctx.frameIndex, draws);
}

void GpuScene::updateMeshVertices(const std::vector<uint32_t>& meshes, const std::vector<std::vector<Vertex>>& vertices) {
  VkDeviceSize total = 0;
  for (size_t i = 0; i < meshes.size(); ++i) {
    TL_CHECK(meshes[i] < meshes_.size() && vertices[i].size() == meshes_[meshes[i]].vertexCount &&
                 previousOffset_[meshes[i]] != shared::kNoPreviousPositions,
             "vertex update of mesh {} does not match its vertex count or it does not deform", meshes[i]);
    total += vertices[i].size() * sizeof(Vertex);
  }
  // Last frame's positions for the motion vectors: those the updated meshes had, and for meshes
  // that moved last time but not now their present ones (they stand still again).
  std::vector<uint32_t> previousOf = meshes;
  for (uint32_t m : movedLastUpdate_)
    if (std::find(meshes.begin(), meshes.end(), m) == meshes.end()) previousOf.push_back(m);
  for (uint32_t m : previousOf) total += uploadedPositions_[m].size() * sizeof(glm::vec4);
  movedLastUpdate_ = meshes;
  if (total == 0) return;
  gpu::Buffer staging(device_, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, gpu::MemoryUsage::Upload, "scene.vertexUpdate");
  std::vector<VkBufferCopy> previousRegions;
  VkDeviceSize at = 0;
  for (uint32_t m : previousOf) {
    const VkDeviceSize bytes = uploadedPositions_[m].size() * sizeof(glm::vec4);
    staging.write(uploadedPositions_[m].data(), bytes, at);
    previousRegions.push_back({at, VkDeviceSize(previousOffset_[m]) * sizeof(glm::vec4), bytes});
    at += bytes;
  }
  std::vector<VkBufferCopy> regions;
  for (size_t i = 0; i < meshes.size(); ++i) {
    const VkDeviceSize bytes = vertices[i].size() * sizeof(Vertex);
    staging.write(vertices[i].data(), bytes, at);
    regions.push_back({at, VkDeviceSize(meshes_[meshes[i]].vertexOffset) * sizeof(Vertex), bytes});
    at += bytes;
    ++meshVersions_[meshes[i]];
    auto& uploaded = uploadedPositions_[meshes[i]];
    for (size_t v = 0; v < uploaded.size(); ++v) uploaded[v] = glm::vec4(vertices[i][v].position, 1.0f);
  }
  device_.immediate([&](VkCommandBuffer cmd) {
    if (!previousRegions.empty())
      vkCmdCopyBuffer(cmd, staging.handle(), previousPositions_.handle(), uint32_t(previousRegions.size()), previousRegions.data());
    if (!regions.empty()) vkCmdCopyBuffer(cmd, staging.handle(), vertices_.handle(), uint32_t(regions.size()), regions.data());
  });
  if (!meshes.empty()) ++geometryVersion_;
}

VkDeviceSize GpuScene::bytes() const {
  VkDeviceSize total = vertices_.size() + indices_.size() + materials_.size() + instances_.size();
  for (auto& t : textures_)
    total += VkDeviceSize(t.extent().width) * t.extent().height * gpu::formatInfo(t.info().format).bytes * 4 / 3;
  return total;
}

}  // namespace tl::scene
