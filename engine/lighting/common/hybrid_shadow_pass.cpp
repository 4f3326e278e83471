#include "lighting/common/hybrid_shadow_pass.h"

#include "lighting/common/gbuffer_pass.h"
#include "lighting/common/pass_builders.h"
#include "lighting/common/shadow_pass.h"
#include "shared/frame.h"
#include "shared/hybrid_shadow.h"

namespace tl::lighting {

bool addHybridSunShadow(graph::RenderGraph& graph, FrameInputs& in, const LightingOutputs& path) {
  // The pass's ray query treats every triangle as opaque (it has no material tables to test a
  // cut-out's alpha, as the rt path's any-hit shader does): a scene with alpha MASK or BLEND keeps the
  // map, which tests them, rather than get a card's or a pane's full shadow.
  const bool hybrid = in.settings.hybridShadows && (in.constants.flags & shared::kFrameFlagSunShadows) != 0 &&
                      path.shadowTlasHandle != VK_NULL_HANDLE && !path.shadowStructures.empty() &&
                      in.scene.alphaTestedInstances().empty();
  if (!hybrid) return false;
  const uint32_t w = in.settings.width, h = in.settings.height;
  shared::HybridShadowPush push{};
  push.hardPenumbraTexels = in.settings.hybridShadowHardTexels;
  ComputePass(in.device, "shadow.sun.hybrid", "common/sun_shadow_hybrid.comp")
      .uniform(shared::kBindingFrame, kFrameConstants)
      .sampled(shared::kHybridShadowNormal, gbuffer::kNormal)
      .sampled(shared::kHybridShadowDepth, gbuffer::kDepth)
      .sampled(shared::kHybridShadowMap, kShadowSunDepth, samplers::sunShadowCompare)
      .sampled(shared::kHybridShadowMapDepth, kShadowSunDepth)
      .accelerationStructure(shared::kHybridShadowTlas, path.shadowTlasHandle, path.shadowStructures)
      .storageOut(shared::kHybridShadowOutput, kShadowSunVisibility,
                  in.screenImage(VK_FORMAT_R16_SFLOAT,
                                 "the sun's visibility: HRTS, ray near contacts, PCSS further (0: facing away)"))
      .push(push)
      .dispatch(w, h)
      .add(graph);
  return true;
}

}  // namespace tl::lighting
