// The G-buffer: every channel declared once in one table (name, format, meaning). The
// pass rasterises all instances into these named resources.
#pragma once

#include "gpu/pipeline.h"
#include "graph/graph.h"
#include "lighting/common/frame_inputs.h"
#include "shared/gbuffer.h"

namespace tl::lighting {

struct GbufferChannel {
  const char* name;
  VkFormat format;
  uint32_t location;  // colour attachment location (shared/gbuffer.h)
  const char* description;
  const char* decoder = "";   // lighting/common/decoders.h, for the viewer's probe
  const char* channels = "";  // conventional channel names in captures (graph::ResourceDesc::channels)
};

inline constexpr GbufferChannel kGbufferChannels[] = {
    {"gbuffer.baseColor", VK_FORMAT_R8G8B8A8_SRGB, shared::kGbufferBaseColor, "base colour, linear once sampled; a the dielectric's F90 (KHR_materials_specular; 1: glTF's core model)"},
    {"gbuffer.normal", VK_FORMAT_R16G16_SNORM, shared::kGbufferNormal, "world shading normal, octahedral", "oct-normal"},
    {"gbuffer.material", VK_FORMAT_R8G8B8A8_UNORM, shared::kGbufferMaterial, "r roughness, g metalness, b sqrt of the dielectric's F0 (KHR_materials_ior/specular; 0.2: glTF's 0.04), a the material's occlusion (glTF occlusionTexture; 1: none)", "",
     "roughness metalness B A"},
    {"gbuffer.emissive", VK_FORMAT_R16G16B16A16_SFLOAT, shared::kGbufferEmissive, "emitted radiance; a coverage"},
    {"gbuffer.motion", VK_FORMAT_R16G16_SFLOAT, shared::kGbufferMotion, "screen motion in UV, current - previous", "",
     "motion.u motion.v"},
    {"gbuffer.instanceId", VK_FORMAT_R32_UINT, shared::kGbufferInstanceId, "instance index + 1, 0 where empty", "instance-id",
     "id"},
};
inline constexpr const char* kGbufferDepth = "gbuffer.depth";  // D32F, reversed Z (1 near, 0 far)

class GbufferPass {
 public:
  void add(graph::RenderGraph& graph, FrameInputs& in);
};

}  // namespace tl::lighting
