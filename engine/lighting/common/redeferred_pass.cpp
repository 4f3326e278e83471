#include "lighting/common/redeferred_pass.h"

#include "graph/executor.h"
#include "lighting/common/composite_pass.h"
#include "lighting/common/decoders.h"
#include "lighting/common/gbuffer_pass.h"
#include "lighting/common/shadow_pass.h"
#include "shared/brdf_lut.h"
#include "shared/redeferred.h"

namespace tl::lighting {

using graph::Usage;

namespace {
constexpr const char* kStandIn = "gbuffer.baseColor";  // fills a binding the shader does not read
constexpr const char* kQuantityName[4] = {"dg", "sg1", "sg2", "ms"};
constexpr uint32_t kOutBinding[4] = {shared::kIbufferOutDg, shared::kIbufferOutSg1, shared::kIbufferOutSg2,
                                     shared::kIbufferOutMs};
constexpr uint32_t kSampledBinding[4] = {shared::kIbufferLightsDg, shared::kIbufferLightsSg1,
                                         shared::kIbufferLightsSg2, shared::kIbufferLightsMs};
constexpr const char* kDescription[4] = {
    "I-buffer: the diffuse layer's share of the light, sum of E n.l (1 - E_d(mu_i))",
    "I-buffer: the single-scattering lobe with F = 1, sum of E n.l D V",
    "I-buffer: the single-scattering lobe times Schlick's weight, sum of E n.l D V (1 - v.h)^5",
    "I-buffer: the multiple-scattering lobe's share, sum of E n.l (1 - E(mu_i))"};
}  // namespace

std::string ibufferDecoder(size_t quantity) { return std::string(kIbufferDecoderPrefix) + kQuantityName[quantity]; }

void RedeferredPass::add(graph::RenderGraph& graph, FrameInputs& in, const shared::CompositePush& push,
                         const CompositePathInputs& inputs, const std::string& output,
                         const graph::ResourceDesc& outputDesc, VkSampler point, VkSampler shadowCompare) {
  addLight(graph, in, push, inputs, point, shadowCompare);
  addLightOnly(graph, in, point);
  if (!material_) {
    const auto sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    gpu::ComputePipelineDesc d;
    d.name = "redeferred.material";
    d.shader = "common/redeferred_material.comp";
    d.layout.bindings = {{shared::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                         {shared::kCompositeBaseColor, sampled},
                         {shared::kCompositeNormal, sampled},
                         {shared::kCompositeMaterial, sampled},
                         {shared::kCompositeEmissive, sampled},
                         {shared::kCompositeDepth, sampled},
                         {shared::kCompositeOutput, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                         {shared::kBindingBrdfTables, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}};
    for (uint32_t b : kSampledBinding) d.layout.bindings.push_back({b, sampled});
    for (const auto& b : CompositePathInputs::bindings()) d.layout.bindings.push_back(b);
    d.layout.pushConstantBytes = sizeof(shared::CompositePush);
    material_ = gpu::createComputePipeline(in.device, d);
  }
  graph.addPass(
      "redeferred.material", graph::PassKind::Compute,
      [&](graph::PassBuilder& b) {
        b.read(kFrameConstants, Usage::StorageRead);
        b.read(kBrdfTables, Usage::StorageRead);
        for (const char* n : {"gbuffer.baseColor", "gbuffer.normal", "gbuffer.material", "gbuffer.emissive"})
          b.read(n, Usage::Sampled);
        b.read(kGbufferDepth, Usage::Sampled);
        for (const char* n : kIbuffer) b.read(n, Usage::Sampled);
        inputs.declareReads(b, "gbuffer.baseColor");
        b.create(output, outputDesc, Usage::StorageWrite);
      },
      [this, &in, push, inputs, output, point](graph::PassContext& ctx) {
        const VkImageLayout ro = VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL;
        ctx.bind(material_);
        auto& d = ctx.descriptors()
                      .uniformBuffer(shared::kBindingFrame, in.constantsBuffer.handle())
                      .sampledImage(shared::kCompositeBaseColor, ctx.image("gbuffer.baseColor").view(), point, ro)
                      .sampledImage(shared::kCompositeNormal, ctx.image("gbuffer.normal").view(), point, ro)
                      .sampledImage(shared::kCompositeMaterial, ctx.image("gbuffer.material").view(), point, ro)
                      .sampledImage(shared::kCompositeEmissive, ctx.image("gbuffer.emissive").view(), point, ro)
                      .sampledImage(shared::kCompositeDepth, ctx.image(kGbufferDepth).view(), point, ro)
                      .storageImage(shared::kCompositeOutput, ctx.image(output).view())
                      .storageBuffer(shared::kBindingBrdfTables, ctx.buffer(kBrdfTables).handle());
        for (size_t q = 0; q < kIbuffer.size(); ++q)
          d.sampledImage(kSampledBinding[q], ctx.image(kIbuffer[q]).view(), point, ro);
        inputs.bind(ctx, point);
        ctx.pushConstants(push);
        ctx.dispatch(in.settings.width, in.settings.height);
      });
}

void RedeferredPass::addLight(graph::RenderGraph& graph, FrameInputs& in, const shared::CompositePush& push,
                              const CompositePathInputs& inputs, VkSampler point, VkSampler shadowCompare) {
  if (!light_) {
    const auto sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    gpu::ComputePipelineDesc d;
    d.name = "ibuffer.light";
    d.shader = "common/ibuffer_light.comp";
    d.layout.bindings = {{shared::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                         {shared::kIbufferNormal, sampled},
                         {shared::kIbufferMaterial, sampled},
                         {shared::kIbufferDepth, sampled},
                         {shared::kIbufferShadow, sampled},
                         {shared::kIbufferShadowDepth, sampled},
                         {shared::kBindingBrdfTables, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}};
    for (uint32_t b : kOutBinding) d.layout.bindings.push_back({b, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE});
    for (uint32_t b : kSampledBinding) d.layout.bindings.push_back({b, sampled});
    for (const auto& b : CompositePathInputs::bindings()) d.layout.bindings.push_back(b);
    d.layout.pushConstantBytes = sizeof(shared::CompositePush);
    light_ = gpu::createComputePipeline(in.device, d);
  }
  const uint32_t w = in.settings.width, h = in.settings.height;
  const bool sun = (in.constants.flags & shared::kFrameFlagSunShadows) != 0;
  const bool lights = (push.flags & shared::kCompositeHasLights) != 0;
  graph.addPass(
      "ibuffer.light", graph::PassKind::Compute,
      [&](graph::PassBuilder& b) {
        b.read(kFrameConstants, Usage::StorageRead);
        b.read(kBrdfTables, Usage::StorageRead);
        for (const char* n : {"gbuffer.normal", "gbuffer.material"}) b.read(n, Usage::Sampled);
        b.read(kGbufferDepth, Usage::Sampled);
        if (sun) b.read(kShadowSunDepth, Usage::Sampled);
        if (lights)
          for (const char* n : kLightsIbuffer) b.read(n, Usage::Sampled);
        inputs.declareReads(b);
        for (size_t q = 0; q < kIbuffer.size(); ++q)
          b.create(kIbuffer[q],
                   graph::ResourceDesc::image2D(VK_FORMAT_R32G32B32A32_SFLOAT, w, h, kDescription[q]).decodedAs(ibufferDecoder(q)),
                   Usage::StorageWrite);
      },
      [this, &in, push, inputs, sun, lights, point, shadowCompare](graph::PassContext& ctx) {
        const VkImageLayout ro = VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL;
        // The binding must still hold a depth image; the G-buffer's depth stands in, unread.
        const gpu::Image& shadow = ctx.image(sun ? kShadowSunDepth : kGbufferDepth);
        ctx.bind(light_);
        auto& d = ctx.descriptors()
                      .uniformBuffer(shared::kBindingFrame, in.constantsBuffer.handle())
                      .sampledImage(shared::kIbufferNormal, ctx.image("gbuffer.normal").view(), point, ro)
                      .sampledImage(shared::kIbufferMaterial, ctx.image("gbuffer.material").view(), point, ro)
                      .sampledImage(shared::kIbufferDepth, ctx.image(kGbufferDepth).view(), point, ro)
                      .sampledImage(shared::kIbufferShadow, shadow.view(), shadowCompare, ro)
                      .sampledImage(shared::kIbufferShadowDepth, shadow.view(), point, ro)
                      .storageBuffer(shared::kBindingBrdfTables, ctx.buffer(kBrdfTables).handle());
        for (size_t q = 0; q < kIbuffer.size(); ++q) {
          d.storageImage(kOutBinding[q], ctx.image(kIbuffer[q]).view());
          d.sampledImage(kSampledBinding[q], ctx.image(lights ? kLightsIbuffer[q] : kStandIn).view(), point, ro);
        }
        inputs.bind(ctx, point);
        ctx.pushConstants(push);
        ctx.dispatch(in.settings.width, in.settings.height);
      });
}

void RedeferredPass::addLightOnly(graph::RenderGraph& graph, FrameInputs& in, VkSampler point) {
  if (!lightOnly_) {
    const auto sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    gpu::ComputePipelineDesc d;
    d.name = "ibuffer.lightOnly";
    d.shader = "common/ibuffer_light_only.comp";
    d.layout.bindings = {{shared::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                         {shared::kIbufferNormal, sampled},
                         {shared::kIbufferMaterial, sampled},
                         {shared::kIbufferDepth, sampled},
                         {shared::kBindingBrdfTables, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                         {shared::kIbufferOutDg, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}};
    for (uint32_t b : kSampledBinding) d.layout.bindings.push_back({b, sampled});
    lightOnly_ = gpu::createComputePipeline(in.device, d);
  }
  const uint32_t w = in.settings.width, h = in.settings.height;
  graph.addPass(
      "ibuffer.lightOnly", graph::PassKind::Compute,
      [&](graph::PassBuilder& b) {
        b.read(kFrameConstants, Usage::StorageRead);
        b.read(kBrdfTables, Usage::StorageRead);
        for (const char* n : {"gbuffer.normal", "gbuffer.material"}) b.read(n, Usage::Sampled);
        b.read(kGbufferDepth, Usage::Sampled);
        for (const char* n : kIbuffer) b.read(n, Usage::Sampled);
        b.create(kIbufferLightOnly,
                 graph::ResourceDesc::image2D(VK_FORMAT_R32G32B32A32_SFLOAT, w, h,
                                              "light only: the I-buffer resolved against white (no materials)"),
                 Usage::StorageWrite);
      },
      [this, &in, point](graph::PassContext& ctx) {
        const VkImageLayout ro = VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL;
        ctx.bind(lightOnly_);
        auto& d = ctx.descriptors()
                      .uniformBuffer(shared::kBindingFrame, in.constantsBuffer.handle())
                      .sampledImage(shared::kIbufferNormal, ctx.image("gbuffer.normal").view(), point, ro)
                      .sampledImage(shared::kIbufferMaterial, ctx.image("gbuffer.material").view(), point, ro)
                      .sampledImage(shared::kIbufferDepth, ctx.image(kGbufferDepth).view(), point, ro)
                      .storageBuffer(shared::kBindingBrdfTables, ctx.buffer(kBrdfTables).handle())
                      .storageImage(shared::kIbufferOutDg, ctx.image(kIbufferLightOnly).view());
        for (size_t q = 0; q < kIbuffer.size(); ++q) d.sampledImage(kSampledBinding[q], ctx.image(kIbuffer[q]).view(), point, ro);
        ctx.dispatch(in.settings.width, in.settings.height);
      });
}

}  // namespace tl::lighting
