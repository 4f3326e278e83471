#include "lighting/common/redeferred_pass.h"

#include "graph/executor.h"
#include "lighting/common/composite_pass.h"
#include "lighting/common/decoders.h"
#include "lighting/common/environment_table.h"
#include "lighting/common/gbuffer_pass.h"
#include "lighting/common/hybrid_shadow_pass.h"
#include "lighting/common/pass_builders.h"
#include "lighting/common/shadow_pass.h"
#include "shared/brdf_lut.h"
#include "shared/redeferred.h"

#include <stdexcept>

namespace tl::lighting {

namespace {
constexpr const char* kQuantityName[4] = {"dg", "sg1", "sg2", "ms"};
constexpr uint32_t kOutBinding[4] = {shared::kIbufferOutDg, shared::kIbufferOutSg1, shared::kIbufferOutSg2,
                                     shared::kIbufferOutMs};
constexpr uint32_t kFilledBinding[4] = {shared::kIbufferFilledDg, shared::kIbufferFilledSg1, shared::kIbufferFilledSg2,
                                        shared::kIbufferFilledMs};
// The light table's share of each sum, sampled by ibuffer.light; sums of the I-buffer (the
// pattern's, or the finished ones), sampled by the passes that read them.
constexpr uint32_t kLightsShareBinding[4] = {shared::kIbufferLightsDg, shared::kIbufferLightsSg1,
                                             shared::kIbufferLightsSg2, shared::kIbufferLightsMs};
constexpr uint32_t kSumBinding[4] = {shared::kIbufferSumDg, shared::kIbufferSumSg1, shared::kIbufferSumSg2,
                                     shared::kIbufferSumMs};
constexpr const char* kDescription[4] = {
    "I-buffer: the diffuse layer's share of the light, sum of E n.l (1 - E_d(mu_i))",
    "I-buffer: the single-scattering lobe with F = 1, sum of E n.l D V",
    "I-buffer: the single-scattering lobe times Schlick's weight, sum of E n.l D V (1 - v.h)^5",
    "I-buffer: the multiple-scattering lobe's share, sum of E n.l (1 - E(mu_i))"};
}  // namespace

std::string ibufferDecoder(size_t quantity) { return std::string(kIbufferDecoderPrefix) + kQuantityName[quantity]; }

namespace {

// The bindings every I-buffer pass shares: frame constants, BRDF tables and the G-buffer
// surface (normal, material, depth) it shades or fills.
void addIbufferSurface(ComputePass& pass) {
  pass.uniform(shared::kBindingFrame, kFrameConstants)
      .bufferIn(shared::kBindingBrdfTables, kBrdfTables)
      .sampled(shared::kIbufferNormal, gbuffer::kNormal)
      .sampled(shared::kIbufferMaterial, gbuffer::kMaterial)
      .sampled(shared::kIbufferDepth, gbuffer::kDepth);
}

}  // namespace

void RedeferredPass::add(graph::RenderGraph& graph, FrameInputs& in, const shared::CompositePush& push,
                         const LightingOutputs& path, graph::ImageName output, const graph::ResourceDesc& outputDesc) {
  // Below full rate: the pattern's pixels, the rest filled, then the edges shaded after all.
  const uint32_t pattern = shared::tlIbufferPattern(in.settings.redeferredRate);
  if (pattern == shared::kIbufferPatternEvery) {
    addLight(graph, in, push, path, shared::kIbufferStageEvery);
  } else {
    addLight(graph, in, push, path, shared::kIbufferStagePattern);
    addUpsample(graph, in, pattern);
    if ((push.flags & shared::kCompositeHasLights) != 0) {
      if (!in.refineLights) throw std::logic_error("redeferred below full rate: lights.direct has no refining run");
      in.refineLights(graph);
    }
    addLight(graph, in, push, path, shared::kIbufferStageRefine);
  }
  addLightOnly(graph, in);
  ComputePass pass(in.device, "redeferred.material", "common/redeferred_material.comp");
  addCompositeGbuffer(pass);
  pass.sampled(shared::kCompositeEmissive, gbuffer::kEmissive)
      .optionalBufferIn(shared::kBindingEnvironment, kEnvironmentTable, hasEnvironmentMap(in))  // the background
      .storageOut(shared::kCompositeOutput, output, outputDesc);
  for (size_t q = 0; q < kIbuffer.size(); ++q) pass.sampled(kSumBinding[q], kIbuffer[q]);
  addPathInputs(pass, path, push.flags);
  pass.push(push).dispatch(in.settings.width, in.settings.height).add(graph);
}

void RedeferredPass::addLight(graph::RenderGraph& graph, FrameInputs& in, const shared::CompositePush& compositePush,
                              const LightingOutputs& path, uint32_t stage) {
  const uint32_t w = in.settings.width, h = in.settings.height;
  const bool refine = stage == shared::kIbufferStageRefine;
  shared::CompositePush push = compositePush;
  push.ibufferStage = stage;
  push.ibufferPattern = shared::tlIbufferPattern(in.settings.redeferredRate);
  // What this run writes and which share of the light table it adds (see kIbufferShaded).
  const auto& outputs = stage == shared::kIbufferStagePattern ? kIbufferShaded : kIbuffer;
  const auto& lightsShare = refine ? kLightsRefined : kLightsIbuffer;
  // The shader reads the sun's map only with kFrameFlagSunShadows, the light table's share
  // only with kCompositeHasLights, the mask and the filled sums only in the refining run.
  const bool sun = (in.constants.flags & shared::kFrameFlagSunShadows) != 0;
  const bool lights = (push.flags & shared::kCompositeHasLights) != 0;
  const bool hybrid = (push.flags & shared::kCompositeHasSunVisibility) != 0;
  ComputePass pass(in.device, refine ? "ibuffer.light.refine" : "ibuffer.light", "common/ibuffer_light.comp");
  addIbufferSurface(pass);
  pass.optionalSampled(shared::kIbufferShadow, kShadowSunDepth, sun && !hybrid, samplers::sunShadowCompare)
      .optionalSampled(shared::kIbufferShadowDepth, kShadowSunDepth, sun && !hybrid)
      .optionalSampled(shared::kIbufferSunVisibility, kShadowSunVisibility, hybrid)
      .optionalSampled(shared::kIbufferRefineMaskSampled, kIbufferRefine, refine);
  for (size_t q = 0; q < kIbuffer.size(); ++q)
    pass.storageOut(kOutBinding[q], outputs[q],
                    in.screenImage(VK_FORMAT_R32G32B32A32_SFLOAT,
                                   stage == shared::kIbufferStagePattern
                                       ? std::string(kDescription[q]) + "; the pattern's pixels only"
                                       : std::string(kDescription[q]))
                        .decodedAs(ibufferDecoder(q)))
        .optionalSampled(kLightsShareBinding[q], lightsShare[q], lights)
        .optionalSampled(kFilledBinding[q], kIbufferFilled[q], refine);
  addPathInputs(pass, path, push.flags);
  const glm::uvec2 grid = stage == shared::kIbufferStagePattern
                              ? shared::tlIbufferPatternGrid(glm::uvec2(w, h), push.ibufferPattern)
                              : glm::uvec2(w, h);
  pass.push(push).dispatch(grid.x, grid.y).add(graph);
}

// The pattern's gaps filled from their shaded neighbours, or marked for the refining run
// (shaders/common/ibuffer_upsample.comp).
void RedeferredPass::addUpsample(graph::RenderGraph& graph, FrameInputs& in, uint32_t pattern) {
  const uint32_t w = in.settings.width, h = in.settings.height;
  shared::IbufferUpsamplePush push{};
  push.pattern = pattern;
  ComputePass pass(in.device, "ibuffer.upsample", "common/ibuffer_upsample.comp");
  addIbufferSurface(pass);  // the BRDF table there: ibuffer_upsample.comp declares it (the old layout left it out)
  pass.storageOut(
      shared::kIbufferRefineMask, kIbufferRefine,
      in.screenImage(VK_FORMAT_R32_SFLOAT,
                     "how each pixel's I-buffer was made: 0 shaded (pattern, sky), 1 filled, 2 shaded as an edge"));
  for (size_t q = 0; q < kIbufferFilled.size(); ++q)
    pass.sampled(kSumBinding[q], kIbufferShaded[q])
        .storageOut(kOutBinding[q], kIbufferFilled[q],
                    in.screenImage(VK_FORMAT_R32G32B32A32_SFLOAT,
                                   std::string(kDescription[q]) + "; filled below full rate (edges still 0)")
                        .decodedAs(ibufferDecoder(q)));
  pass.push(push).dispatch(w, h).add(graph);
}

void RedeferredPass::addLightOnly(graph::RenderGraph& graph, FrameInputs& in) {
  const uint32_t w = in.settings.width, h = in.settings.height;
  ComputePass pass(in.device, "ibuffer.lightOnly", "common/ibuffer_light_only.comp");
  addIbufferSurface(pass);
  pass.optionalBufferIn(shared::kBindingEnvironment, kEnvironmentTable, hasEnvironmentMap(in));  // the background
  pass.storageOut(
      shared::kIbufferLightOnlyOut, kIbufferLightOnly,
      in.screenImage(VK_FORMAT_R32G32B32A32_SFLOAT, "light only: the I-buffer resolved against white (no materials)"));
  for (size_t q = 0; q < kIbuffer.size(); ++q) pass.sampled(kSumBinding[q], kIbuffer[q]);
  pass.dispatch(w, h).add(graph);
}

}  // namespace tl::lighting
