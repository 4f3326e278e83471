// The composite shared by every lighting path: sun (with the shadow map), sky multiplied
// by AO, diffuse and specular indirect light from the path's outputs, and emission, into
// scene-linear radiance. Then the tonemap turns radiance into the display image.
#pragma once

#include "gpu/pipeline.h"
#include "graph/graph.h"
#include "lighting/common/frame_inputs.h"
#include "lighting/common/pass_builders.h"
#include "lighting/common/redeferred_pass.h"
#include "lighting/lighting_path.h"
#include "shared/gbuffer.h"

namespace tl::lighting {

inline constexpr graph::ImageName kCompositeHdr{"composite.hdr"};  // scene-linear radiance, kCompositeHdrFormat
// The final radiance and every copy of it (TAA's input and history, the paths' radiance
// histories, compare's kept images, the albedo baseline) are 32-bit floats: half floats
// saturated at 65504, so a sun of 1e6 (radiance 3e5) was clipped silently in 63-67% of the
// pixels of an EXR. The GLSL writers say rgba32f (composite.comp, taa.comp).
inline constexpr VkFormat kCompositeHdrFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr graph::ImageName kTonemapLdr{"tonemap.ldr"};      // RGBA8, sRGB-encoded display image
// What the composite multiplied, as images (composite.stages; run only when read): per-stage
// error against reference.ao and reference.irradiance, and the lobes' split. 0 on sky pixels.
inline constexpr graph::ImageName kCompositeAo{"composite.ao"};                  // R16F
inline constexpr graph::ImageName kCompositeIrradiance{"composite.irradiance"};  // RGBA16F, sky + bounce, no sun
// The radiance through the surface's diffuse layer and through its specular lobes (RGBA16F):
// the split of reference.diffuse and reference.specular. Emission is in neither.
inline constexpr graph::ImageName kCompositeDiffuseLobe{"composite.diffuse"};
inline constexpr graph::ImageName kCompositeSpecularLobe{"composite.specular"};

// The path's images every pass that includes shaders/common/path_indirect.glsl samples (the
// composite, its stages, redeferred shading's ibuffer.light and redeferred.material): optional
// inputs, bound where the path made them; `flags` (CompositePush::flags) tell the shader which.
void addPathInputs(ComputePass& pass, const LightingOutputs& path, uint32_t flags);
// The frame, the BRDF tables and the G-buffer's base colour, normal, material and depth at the
// composite's bindings (shared/gbuffer.h kComposite*), as the composite, its stages and
// redeferred.material read them (the emission, where a pass reads it, is its own line).
void addCompositeGbuffer(ComputePass& pass);

class CompositePass {
 public:
  void add(graph::RenderGraph& graph, FrameInputs& in, const LightingOutputs& path);

 private:
  void addStages(graph::RenderGraph& graph, FrameInputs& in, const shared::CompositePush& push,
                 const LightingOutputs& path);

  RedeferredPass redeferred_;
};

class TonemapPass {
 public:
  void add(graph::RenderGraph& graph, FrameInputs& in);
};

}  // namespace tl::lighting
