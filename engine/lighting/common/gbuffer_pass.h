// The G-buffer: every channel declared once in one table (name, format, meaning). The
// pass rasterises all instances into these named resources.
#pragma once

#include "gpu/pipeline.h"
#include "graph/graph.h"
#include "lighting/common/frame_inputs.h"
#include "shared/gbuffer.h"

namespace tl::lighting {

// The G-buffer's resources by what they hold: every pass that reads the G-buffer binds these.
namespace gbuffer {
inline constexpr graph::ImageName kBaseColor{"gbuffer.baseColor"};
inline constexpr graph::ImageName kNormal{"gbuffer.normal"};
inline constexpr graph::ImageName kMaterial{"gbuffer.material"};
inline constexpr graph::ImageName kEmissive{"gbuffer.emissive"};
inline constexpr graph::ImageName kMotion{"gbuffer.motion"};
inline constexpr graph::ImageName kInstanceId{"gbuffer.instanceId"};
inline constexpr graph::ImageName kDepth{"gbuffer.depth"};  // D32F, reversed Z (1 near, 0 far)
}  // namespace gbuffer

struct GbufferChannel {
  graph::ImageName name;
  VkFormat format;
  uint32_t location;  // colour attachment location (shared/gbuffer.h)
  const char* description;
  const char* decoder = "";   // lighting/common/decoders.h, for the viewer's probe
  const char* channels = "";  // conventional channel names in captures (graph::ResourceDesc::channels)
};

// The colour attachments, in location order (the depth is gbuffer::kDepth).
inline constexpr GbufferChannel kGbufferChannels[] = {
    {gbuffer::kBaseColor, VK_FORMAT_R8G8B8A8_SRGB, shared::kGbufferBaseColor, "base colour, linear once sampled; a the dielectric's F90 (KHR_materials_specular; 1: glTF's core model)"},
    {gbuffer::kNormal, VK_FORMAT_R16G16_SNORM, shared::kGbufferNormal, "world shading normal, octahedral", "oct-normal"},
    {gbuffer::kMaterial, VK_FORMAT_R8G8B8A8_UNORM, shared::kGbufferMaterial, "r roughness, g metalness, b sqrt of the dielectric's F0 (KHR_materials_ior/specular; 0.2: glTF's 0.04), a the material's occlusion (glTF occlusionTexture; 1: none)", "",
     "roughness metalness B A"},
    {gbuffer::kEmissive, VK_FORMAT_R16G16B16A16_SFLOAT, shared::kGbufferEmissive, "emitted radiance; a coverage"},
    {gbuffer::kMotion, VK_FORMAT_R16G16_SFLOAT, shared::kGbufferMotion, "screen motion in UV, current - previous", "",
     "motion.u motion.v"},
    {gbuffer::kInstanceId, VK_FORMAT_R32_UINT, shared::kGbufferInstanceId, "instance index + 1, 0 where empty", "instance-id",
     "id"},
};

class GbufferPass {
 public:
  void add(graph::RenderGraph& graph, FrameInputs& in);
};

}  // namespace tl::lighting
