// The composite shared by every lighting path: sun (with the shadow map), sky multiplied
// by AO, diffuse and specular indirect light from the path's outputs, and emission, into
// scene-linear radiance. Then the tonemap turns radiance into the display image.
#pragma once

#include "gpu/pipeline.h"
#include "graph/graph.h"
#include "lighting/common/frame_inputs.h"
#include "lighting/lighting_path.h"
#include "shared/gbuffer.h"

namespace tl::lighting {

inline constexpr const char* kCompositeHdr = "composite.hdr";  // RGBA16F scene-linear radiance
inline constexpr const char* kTonemapLdr = "tonemap.ldr";      // RGBA8, sRGB-encoded display image
// What the composite multiplied, as images (composite.stages; run only when read): per-stage
// error against reference.ao and reference.irradiance. 0 on sky pixels.
inline constexpr const char* kCompositeAo = "composite.ao";                  // R16F
inline constexpr const char* kCompositeIrradiance = "composite.irradiance";  // RGBA16F, sky + bounce, no sun

class CompositePass {
 public:
  void add(graph::RenderGraph& graph, FrameInputs& in, const LightingOutputs& path);

 private:
  struct FarField {
    std::string shY, coCg, ao;
  };
  void addStages(graph::RenderGraph& graph, FrameInputs& in, const shared::CompositePush& push, const std::string& ao,
                 const std::string& shY, const std::string& coCg, const FarField& farField);

  gpu::Pipeline pipeline_;
  gpu::Pipeline stagesPipeline_;
  gpu::Sampler pointSampler_;
  gpu::Sampler shadowSampler_;
};

class TonemapPass {
 public:
  void add(graph::RenderGraph& graph, FrameInputs& in);

 private:
  gpu::Pipeline pipeline_;
  gpu::Sampler pointSampler_;
};

}  // namespace tl::lighting
