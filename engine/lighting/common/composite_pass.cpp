#include "lighting/common/composite_pass.h"
#include "lighting/common/taa_pass.h"

#include "graph/executor.h"
#include "lighting/common/environment_table.h"
#include "lighting/common/gbuffer_pass.h"
#include "lighting/common/hybrid_shadow_pass.h"
#include "lighting/common/pass_builders.h"
#include "lighting/common/shadow_pass.h"
#include "shared/brdf_lut.h"


namespace tl::lighting {

using graph::Usage;

// No stand-in fills an absent image: the flags tell the shader which are bound.
void addPathInputs(ComputePass& pass, const LightingOutputs& path, uint32_t flags) {
  const bool gi = (flags & shared::kCompositeHasGi) != 0, far = (flags & shared::kCompositeHasFarGi) != 0;
  const bool ao = (flags & shared::kCompositeHasAo) != 0;
  const bool specular = (flags & shared::kCompositeHasTracedSpecular) != 0;
  pass.optionalSampled(shared::kCompositeAo, graph::ImageName{path.ambientOcclusion}, ao)
      .optionalSampled(shared::kCompositeShY, graph::ImageName{path.diffuseShY}, gi)
      .optionalSampled(shared::kCompositeCoCg, graph::ImageName{path.diffuseCoCg}, gi)
      .optionalSampled(shared::kCompositeFarShY, graph::ImageName{path.farShY}, far)
      .optionalSampled(shared::kCompositeFarCoCg, graph::ImageName{path.farCoCg}, far)
      .optionalSampled(shared::kCompositeFarAo, graph::ImageName{path.farAo}, far)
      .optionalSampled(shared::kCompositeSpecular, graph::ImageName{path.specular}, specular);
}

void addCompositeGbuffer(ComputePass& pass) {
  pass.uniform(shared::kBindingFrame, kFrameConstants)
      .bufferIn(shared::kBindingBrdfTables, kBrdfTables)
      .sampled(shared::kCompositeBaseColor, gbuffer::kBaseColor)
      .sampled(shared::kCompositeNormal, gbuffer::kNormal)
      .sampled(shared::kCompositeMaterial, gbuffer::kMaterial)
      .sampled(shared::kCompositeDepth, gbuffer::kDepth);
}

// The sun's shadow (the map, or hybrid ray-traced shadows' visibility) and lights.direct, as
// `flags` say, at the composite's bindings: the composite and its stages shade the sun and the
// light table from the same images.
void addSunAndLights(ComputePass& pass, const FrameInputs& in, const LightingOutputs& path, uint32_t flags) {
  // Without a sun the shadow map is never sampled (the shaders test kFrameFlagSunShadows):
  // not reading it lets the graph cull the shadow pass.
  const bool sun = (in.constants.flags & shared::kFrameFlagSunShadows) != 0;
  const bool hybrid = (flags & shared::kCompositeHasSunVisibility) != 0;
  pass.optionalSampled(shared::kCompositeShadow, kShadowSunDepth, sun && !hybrid, samplers::sunShadowCompare)
      .optionalSampled(shared::kCompositeShadowDepth, kShadowSunDepth, sun && !hybrid)
      .optionalSampled(shared::kCompositeSunVisibility, kShadowSunVisibility, hybrid)
      .optionalSampled(shared::kCompositeLights, graph::ImageName{path.lightsRadiance},
                       (flags & shared::kCompositeHasLights) != 0);
}

void CompositePass::add(graph::RenderGraph& graph, FrameInputs& in, const LightingOutputs& path) {
  const uint32_t w = in.settings.width, h = in.settings.height;
  const auto hdrDesc = in.screenImage(kCompositeHdrFormat, "scene-linear radiance before exposure");
  if (!path.radiance.empty()) {
    // The path computed the whole image: pass it through (32-bit float -> half).
    TransferPass("composite").blit(graph::ImageName{path.radiance}, kCompositeHdr, hdrDesc).add(graph);
    return;
  }
  shared::CompositePush push{};
  push.flags = (path.ambientOcclusion.empty() ? 0u : shared::kCompositeHasAo) |
               (path.diffuseShY.empty() || path.diffuseCoCg.empty() ? 0u : shared::kCompositeHasGi) |
               (path.aoOnGi ? shared::kCompositeAoOnGi : 0u);
  const bool far = !path.farShY.empty() && !path.farCoCg.empty() && !path.farAo.empty() &&
                   (push.flags & shared::kCompositeHasGi);
  if (far) push.flags |= shared::kCompositeHasFarGi;
  if (in.settings.specularGi) push.flags |= shared::kCompositeSpecularGi;
  if (!path.specular.empty()) push.flags |= shared::kCompositeHasTracedSpecular;
  // The light table's radiance (lights.direct), where the path made it.
  if (!path.lightsRadiance.empty()) push.flags |= shared::kCompositeHasLights;
  // The sun's shadow from hybrid ray-traced shadows where the path has a top level.
  const bool hybrid = addHybridSunShadow(graph, in, path);
  if (hybrid) push.flags |= shared::kCompositeHasSunVisibility;
  push.giBlendDistance = path.giBlendDistance;
  push.openSkyDirectionality = path.openSkyDirectionality;
  push.farOpenSkyDirectionality = path.farOpenSkyDirectionality;
  push.giBlendWidth = kGiBlendWidthFraction * path.giBlendDistance;
  // With TAA the composite is this frame's jittered image; the TAA pass resolves it into
  // composite.hdr (lighting/common/taa_pass.h).
  const graph::ImageName output = in.temporalAntialiasing ? kCompositeUnresolved : kCompositeHdr;
  const auto unresolvedDesc =
      in.screenImage(kCompositeHdrFormat, "scene-linear radiance before exposure, jittered (TAA input)");
  // Redeferred shading (lighting/common/redeferred_pass.h): the same image from the I-buffer.
  if (in.settings.redeferred) {
    redeferred_.add(graph, in, push, path, output, in.temporalAntialiasing ? unresolvedDesc : hdrDesc);
    addStages(graph, in, push, path);
    return;
  }
  ComputePass pass(in.device, "composite", "common/composite.comp");
  addCompositeGbuffer(pass);
  addSunAndLights(pass, in, path, push.flags);
  pass.sampled(shared::kCompositeEmissive, gbuffer::kEmissive)
      .optionalBufferIn(shared::kBindingEnvironment, kEnvironmentTable, hasEnvironmentMap(in))  // the background
      .storageOut(shared::kCompositeOutput, output, in.temporalAntialiasing ? unresolvedDesc : hdrDesc);
  addPathInputs(pass, path, push.flags);
  pass.push(push).dispatch(w, h).add(graph);
  addStages(graph, in, push, path);
}

void CompositePass::addStages(graph::RenderGraph& graph, FrameInputs& in, const shared::CompositePush& push,
                              const LightingOutputs& path) {
  const uint32_t w = in.settings.width, h = in.settings.height;
  ComputePass pass(in.device, "composite.stages", "common/composite_stages.comp");
  addCompositeGbuffer(pass);
  // Redeferred shading's light table comes as the I-buffer's sums, not lights.direct: its
  // stages leave the light table out of the lobes (compare does not split such a run).
  const uint32_t flags = in.settings.redeferred ? push.flags & ~shared::kCompositeHasLights : push.flags;
  addSunAndLights(pass, in, path, flags);
  pass.storageOut(shared::kCompositeStageAo, kCompositeAo,
                  in.screenImage(VK_FORMAT_R16_SFLOAT, "the AO the composite applied (0: sky)").decodedAs("ao"))
      .storageOut(shared::kCompositeStageIrradiance, kCompositeIrradiance,
                  in.screenImage(VK_FORMAT_R16G16B16A16_SFLOAT,
                                 "the diffuse irradiance the composite used: sky + bounce, no sun (0: sky)"))
      .storageOut(shared::kCompositeStageDiffuse, kCompositeDiffuseLobe,
                  in.screenImage(VK_FORMAT_R16G16B16A16_SFLOAT,
                                 "the radiance the surface reflects through its diffuse layer: sun, lights, indirect "
                                 "(0: sky)"))
      .storageOut(shared::kCompositeStageSpecular, kCompositeSpecularLobe,
                  in.screenImage(VK_FORMAT_R16G16B16A16_SFLOAT,
                                 "the radiance the surface reflects through its specular lobes: sun, lights, "
                                 "reflections (0: sky)"));
  shared::CompositePush stagePush = push;
  stagePush.flags = flags;
  addPathInputs(pass, path, flags);
  pass.push(stagePush).dispatch(w, h).add(graph);
}

void TonemapPass::add(graph::RenderGraph& graph, FrameInputs& in) {
  const uint32_t w = in.settings.width, h = in.settings.height;
  ComputePass(in.device, "tonemap", "common/tonemap.comp")
      .uniform(shared::kBindingFrame, kFrameConstants)
      .sampled(shared::kTonemapInput, kCompositeHdr)
      .storageOut(shared::kTonemapOutput, kTonemapLdr,
                  in.screenImage(VK_FORMAT_R8G8B8A8_UNORM, "display image: exposure, ACES, sRGB").displayReferred())
      .dispatch(w, h)
      .add(graph);
  graph.markOutput(kTonemapLdr);
  graph.markOutput(kCompositeHdr);
}

}  // namespace tl::lighting
