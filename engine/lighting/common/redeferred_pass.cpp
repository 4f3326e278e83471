#include "lighting/common/redeferred_pass.h"

#include "graph/executor.h"
#include "lighting/common/composite_pass.h"
#include "lighting/common/decoders.h"
#include "lighting/common/gbuffer_pass.h"
#include "lighting/common/shadow_pass.h"
#include "shared/brdf_lut.h"
#include "shared/redeferred.h"

#include <stdexcept>

namespace tl::lighting {

using graph::Usage;

namespace {
constexpr const char* kStandIn = "gbuffer.baseColor";  // fills a binding the shader does not read
constexpr const char* kQuantityName[4] = {"dg", "sg1", "sg2", "ms"};
constexpr uint32_t kOutBinding[4] = {shared::kIbufferOutDg, shared::kIbufferOutSg1, shared::kIbufferOutSg2,
                                     shared::kIbufferOutMs};
constexpr uint32_t kFilledBinding[4] = {shared::kIbufferFilledDg, shared::kIbufferFilledSg1, shared::kIbufferFilledSg2,
                                        shared::kIbufferFilledMs};
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
  // Below full rate: the pattern's pixels, the rest filled, then the edges shaded after all.
  const uint32_t pattern = shared::tlIbufferPattern(in.settings.redeferredRate);
  if (pattern == shared::kIbufferPatternEvery) {
    addLight(graph, in, push, inputs, point, shadowCompare, shared::kIbufferStageEvery);
  } else {
    addLight(graph, in, push, inputs, point, shadowCompare, shared::kIbufferStagePattern);
    addUpsample(graph, in, pattern, point);
    if ((push.flags & shared::kCompositeHasLights) != 0) {
      if (!in.refineLights) throw std::logic_error("redeferred below full rate: lights.direct has no refining run");
      in.refineLights(graph);
    }
    addLight(graph, in, push, inputs, point, shadowCompare, shared::kIbufferStageRefine);
  }
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

void RedeferredPass::addLight(graph::RenderGraph& graph, FrameInputs& in, const shared::CompositePush& compositePush,
                              const CompositePathInputs& inputs, VkSampler point, VkSampler shadowCompare, uint32_t stage) {
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
    d.layout.bindings.push_back({shared::kIbufferRefineMaskSampled, sampled});
    for (uint32_t b : kFilledBinding) d.layout.bindings.push_back({b, sampled});
    d.layout.pushConstantBytes = sizeof(shared::CompositePush);
    light_ = gpu::createComputePipeline(in.device, d);
  }
  const uint32_t w = in.settings.width, h = in.settings.height;
  const bool refine = stage == shared::kIbufferStageRefine;
  shared::CompositePush push = compositePush;
  push.ibufferStage = stage;
  push.ibufferPattern = shared::tlIbufferPattern(in.settings.redeferredRate);
  // What this run writes and which share of the light table it adds (see kIbufferShaded).
  const auto& outputs = stage == shared::kIbufferStagePattern ? kIbufferShaded : kIbuffer;
  const auto& lightsShare = refine ? kLightsRefined : kLightsIbuffer;
  const bool sun = (in.constants.flags & shared::kFrameFlagSunShadows) != 0;
  const bool lights = (push.flags & shared::kCompositeHasLights) != 0;
  graph.addPass(
      refine ? "ibuffer.light.refine" : "ibuffer.light", graph::PassKind::Compute,
      [&](graph::PassBuilder& b) {
        b.read(kFrameConstants, Usage::StorageRead);
        b.read(kBrdfTables, Usage::StorageRead);
        for (const char* n : {"gbuffer.normal", "gbuffer.material"}) b.read(n, Usage::Sampled);
        b.read(kGbufferDepth, Usage::Sampled);
        if (sun) b.read(kShadowSunDepth, Usage::Sampled);
        if (lights)
          for (const char* n : lightsShare) b.read(n, Usage::Sampled);
        inputs.declareReads(b);
        if (refine) {
          b.read(kIbufferRefine, Usage::Sampled);
          for (const char* n : kIbufferFilled) b.read(n, Usage::Sampled);
        }
        for (size_t q = 0; q < kIbuffer.size(); ++q)
          b.create(outputs[q],
                   graph::ResourceDesc::image2D(VK_FORMAT_R32G32B32A32_SFLOAT, w, h,
                                         stage == shared::kIbufferStagePattern
                                             ? std::string(kDescription[q]) + "; the pattern's pixels only"
                                             : std::string(kDescription[q]))
                .decodedAs(ibufferDecoder(q)),
                   Usage::StorageWrite);
      },
      [this, &in, push, inputs, sun, lights, refine, &outputs, &lightsShare, point, shadowCompare](graph::PassContext& ctx) {
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
          d.storageImage(kOutBinding[q], ctx.image(outputs[q]).view());
          d.sampledImage(kSampledBinding[q], ctx.image(lights ? lightsShare[q] : kStandIn).view(), point, ro);
          d.sampledImage(kFilledBinding[q], ctx.image(refine ? kIbufferFilled[q] : kStandIn).view(), point, ro);
        }
        inputs.bind(ctx, point);
        // Outside the refining run the mask's binding holds the depth, unread.
        d.sampledImage(shared::kIbufferRefineMaskSampled, ctx.image(refine ? kIbufferRefine : kGbufferDepth).view(), point, ro);
        ctx.pushConstants(push);
        const glm::uvec2 grid = push.ibufferStage == shared::kIbufferStagePattern
                                    ? shared::tlIbufferPatternGrid(glm::uvec2(in.settings.width, in.settings.height), push.ibufferPattern)
                                    : glm::uvec2(in.settings.width, in.settings.height);
        ctx.dispatch(grid.x, grid.y);
      });
}

// The pattern's gaps filled from their shaded neighbours, or marked for the refining run
// (shaders/common/ibuffer_upsample.comp).
void RedeferredPass::addUpsample(graph::RenderGraph& graph, FrameInputs& in, uint32_t pattern, VkSampler point) {
  if (!upsample_) {
    const auto sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    gpu::ComputePipelineDesc d;
    d.name = "ibuffer.upsample";
    d.shader = "common/ibuffer_upsample.comp";
    d.layout.bindings = {{shared::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                         {shared::kIbufferNormal, sampled},
                         {shared::kIbufferMaterial, sampled},
                         {shared::kIbufferDepth, sampled},
                         {shared::kIbufferRefineMask, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}};
    for (uint32_t b : kOutBinding) d.layout.bindings.push_back({b, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE});
    for (uint32_t b : kSampledBinding) d.layout.bindings.push_back({b, sampled});
    d.layout.pushConstantBytes = sizeof(shared::IbufferUpsamplePush);
    upsample_ = gpu::createComputePipeline(in.device, d);
  }
  const uint32_t w = in.settings.width, h = in.settings.height;
  shared::IbufferUpsamplePush push{};
  push.pattern = pattern;
  graph.addPass(
      "ibuffer.upsample", graph::PassKind::Compute,
      [&](graph::PassBuilder& b) {
        b.read(kFrameConstants, Usage::StorageRead);
        for (const char* n : {"gbuffer.normal", "gbuffer.material"}) b.read(n, Usage::Sampled);
        b.read(kGbufferDepth, Usage::Sampled);
        for (const char* n : kIbufferShaded) b.read(n, Usage::Sampled);
        for (size_t q = 0; q < kIbufferFilled.size(); ++q)
          b.create(kIbufferFilled[q],
                   graph::ResourceDesc::image2D(VK_FORMAT_R32G32B32A32_SFLOAT, w, h,
                                                std::string(kDescription[q]) + "; filled below full rate (edges still 0)")
                       .decodedAs(ibufferDecoder(q)),
                   Usage::StorageWrite);
        b.create(kIbufferRefine,
                 graph::ResourceDesc::image2D(VK_FORMAT_R32_SFLOAT, w, h,
                                              "how each pixel's I-buffer was made: 0 shaded (pattern, sky), 1 filled, 2 shaded as an edge"),
                 Usage::StorageWrite);
      },
      [this, &in, push, point](graph::PassContext& ctx) {
        const VkImageLayout ro = VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL;
        ctx.bind(upsample_);
        auto& d = ctx.descriptors()
                      .uniformBuffer(shared::kBindingFrame, in.constantsBuffer.handle())
                      .sampledImage(shared::kIbufferNormal, ctx.image("gbuffer.normal").view(), point, ro)
                      .sampledImage(shared::kIbufferMaterial, ctx.image("gbuffer.material").view(), point, ro)
                      .sampledImage(shared::kIbufferDepth, ctx.image(kGbufferDepth).view(), point, ro)
                      .storageImage(shared::kIbufferRefineMask, ctx.image(kIbufferRefine).view());
        for (size_t q = 0; q < kIbuffer.size(); ++q) {
          d.storageImage(kOutBinding[q], ctx.image(kIbufferFilled[q]).view());
          d.sampledImage(kSampledBinding[q], ctx.image(kIbufferShaded[q]).view(), point, ro);
        }
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
