// Redeferred shading (Fools Engine; shared/redeferred.h has the factorisation): instead of the
// composite, an illumination pass (ibuffer.light) sums every light the BRDF's light loop sees
// (the sun, the light table's share from lights.direct in redeferred form, the path's diffuse
// irradiance) into four material-free images, the I-buffer, and a material pass
// (redeferred.material) applies each pixel's material once, adding what does not factor
// (emission, indirect specular, multi-bounce AO's put-back). At full rate it writes the
// composite's image (a GPU test holds them within 1e-3).
#pragma once

#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "graph/graph.h"
#include "lighting/common/frame_inputs.h"
#include "shared/gbuffer.h"

#include <array>
#include <string>

namespace tl::lighting {

struct LightingOutputs;

// The I-buffer, RGBA32F each (rgb: the sum; 0 on the sky): ibuffer.Ldg the diffuse layer's
// share of the light, ibuffer.Lsg1 the single-scattering lobe with F = 1, ibuffer.Lsg2 the same
// times Schlick's weight, ibuffer.Lms the multiple-scattering lobe's share. W/m^2 (weighted).
inline constexpr std::array<graph::ImageName, 4> kIbuffer = {
    graph::ImageName{"ibuffer.Ldg"}, graph::ImageName{"ibuffer.Lsg1"},
    graph::ImageName{"ibuffer.Lsg2"}, graph::ImageName{"ibuffer.Lms"}};
// The light table's share of it (lights.direct in redeferred form), read by ibuffer.light.
inline constexpr std::array<graph::ImageName, 4> kLightsIbuffer = {
    graph::ImageName{"lights.Ldg"}, graph::ImageName{"lights.Lsg1"},
    graph::ImageName{"lights.Lsg2"}, graph::ImageName{"lights.Lms"}};
// The "light only" view: the I-buffer resolved against white (RGBA32F scene-linear radiance;
// the sky where nothing is drawn). Made only in frames that read it.
inline constexpr graph::ImageName kIbufferLightOnly{"ibuffer.lightOnly"};
// Below full rate (`redeferredRate`): how ibuffer.upsample made each pixel's I-buffer (R32F,
// shared/redeferred.h: 0 shaded by the pattern or the sky, 1 filled, 2 shaded as an edge).
inline constexpr graph::ImageName kIbufferRefine{"ibuffer.refine"};
// Below full rate the sums pass through: ibuffer.light writes the pattern's pixels
// (ibuffer.shaded.*), ibuffer.upsample fills the rest (ibuffer.filled.*), the refining run of
// ibuffer.light shades the marked ones into ibuffer.* from them and from the light table's
// refined share (lights.refined.*, lights.direct.refine).
inline constexpr std::array<graph::ImageName, 4> kIbufferShaded = {
    graph::ImageName{"ibuffer.shaded.Ldg"}, graph::ImageName{"ibuffer.shaded.Lsg1"},
    graph::ImageName{"ibuffer.shaded.Lsg2"}, graph::ImageName{"ibuffer.shaded.Lms"}};
inline constexpr std::array<graph::ImageName, 4> kIbufferFilled = {
    graph::ImageName{"ibuffer.filled.Ldg"}, graph::ImageName{"ibuffer.filled.Lsg1"},
    graph::ImageName{"ibuffer.filled.Lsg2"}, graph::ImageName{"ibuffer.filled.Lms"}};
inline constexpr std::array<graph::ImageName, 4> kLightsRefined = {
    graph::ImageName{"lights.refined.Ldg"}, graph::ImageName{"lights.refined.Lsg1"},
    graph::ImageName{"lights.refined.Lsg2"}, graph::ImageName{"lights.refined.Lms"}};
// The decoder of an I-buffer image ("ibuffer" in lighting/common/decoders.h): which sum it holds.
std::string ibufferDecoder(size_t quantity);

class RedeferredPass {
 public:
  // Adds ibuffer.light and redeferred.material; the material pass creates `output` (the
  // composite's image, `outputDesc`). `push` is the composite's; the path's images are bound
  // as the composite binds them (addPathInputs, composite_pass.h).
  void add(graph::RenderGraph& graph, FrameInputs& in, const shared::CompositePush& push, const LightingOutputs& path,
           graph::ImageName output, const graph::ResourceDesc& outputDesc);

 private:
  // `stage`: shared::kIbufferStage* (every pixel, the pattern's, the refined ones).
  void addLight(graph::RenderGraph& graph, FrameInputs& in, const shared::CompositePush& push, const LightingOutputs& path,
                uint32_t stage);
  void addUpsample(graph::RenderGraph& graph, FrameInputs& in, uint32_t pattern);
  void addLightOnly(graph::RenderGraph& graph, FrameInputs& in);
};

}  // namespace tl::lighting
