#include "lighting/common/lights_pass.h"

#include "graph/executor.h"
#include "lighting/common/gbuffer_pass.h"
#include "lighting/common/history.h"
#include "lighting/common/light_shadows.h"
#include "lighting/common/light_table.h"
#include "lighting/common/pass_builders.h"
#include "lighting/common/redeferred_pass.h"
#include "shared/brdf_lut.h"
#include "shared/lights.h"
#include "shared/redeferred.h"

namespace tl::lighting {

namespace {
constexpr HistoryPolicy kLightsAccumulation{
    "lights.accumulation",
    parts(FramePart::CameraPosition, FramePart::CameraOrientation, FramePart::Projection, FramePart::Sun,
          FramePart::Scene, FramePart::Geometry, FramePart::Settings),
    0};

// The bindings both forms of the pass share: the frame, the G-buffer, the BRDF tables, the
// table, and its shadows (rays against the top level, the lights' shadow maps, or none).
void addTableInputs(ComputePass& pass, const std::vector<std::string>& structures, VkAccelerationStructureKHR tlasHandle,
                    bool traced, bool mapped) {
  pass.uniform(shared::kBindingFrame, kFrameConstants)
      .sampled(shared::kLightsPassNormal, gbuffer::kNormal)
      .sampled(shared::kLightsPassMaterial, gbuffer::kMaterial)
      .sampled(shared::kLightsPassDepth, gbuffer::kDepth)
      .bufferIn(shared::kBindingBrdfTables, kBrdfTables)
      .bufferIn(shared::kBindingLights, kLightTable);
  if (traced) pass.accelerationStructure(shared::kLightsPassTlas, tlasHandle, structures);
  if (mapped)
    pass.bufferIn(shared::kBindingLightShadowViews, kLightShadowViews)
        .sampled(shared::kBindingLightShadowAtlas, kLightShadowAtlas, samplers::shadowCompare)
        .sampled(shared::kBindingLightShadowDepth, kLightShadowAtlas, samplers::point);
}

// The table's light is an estimate that changes from frame to frame, accumulated while nothing
// it depends on changes: with more lights than the loop evaluates, or with area lights (their
// glossy reflection is estimated by samples, shared/area_specular.h; their shadows by shadow rays
// to points of the shape or by their map's taps turned each frame).
bool sampledEstimate(const FrameInputs& in) {
  return in.constants.lightCount > shared::kLightsLoopMax || in.areaLights > 0;
}

// Each form has a shader per kind of shadow: <form>.comp, <form>_shadowed.comp, <form>_traced.comp.
std::string shaderFor(const char* form, bool traced, bool mapped) {
  return std::string("common/") + form + (traced ? "_traced" : mapped ? "_shadowed" : "") + ".comp";
}
}  // namespace

VkBuffer lightTableOrStandIn(graph::PassContext& ctx, const FrameInputs& in, VkBuffer standIn) {
  return in.constants.lightCount > 0 ? ctx.buffer(kLightTable).handle() : standIn;
}

std::string LightsPass::add(graph::RenderGraph& graph, FrameInputs& in, const std::vector<std::string>& structures,
                            VkAccelerationStructureKHR tlasHandle) {
  if (in.constants.lightCount == 0) return "";
  if (in.settings.redeferred)
    return addIbuffer(graph, in, structures, tlasHandle,
                      shared::tlIbufferPattern(in.settings.redeferredRate) == shared::kIbufferPatternEvery
                          ? shared::kIbufferStageEvery
                          : shared::kIbufferStagePattern);
  const bool traced = !structures.empty() && tlasHandle != VK_NULL_HANDLE;
  const bool mapped = !traced && in.lightShadowViews > 0;
  const uint32_t w = in.settings.width, h = in.settings.height;
  // Many lights or sampled area shadows: a noisy estimate, accumulated while nothing it depends on changes.
  shared::LightsPush push{};
  const std::string accum = "lights.accum." + in.pathName;
  const std::string accumSpecular = accum + ".specular";
  const auto accumDesc =
      in.screenImage(VK_FORMAT_R32G32B32A32_SFLOAT, "sum of light-table estimates (rgb) and their count (a)");
  const auto accumSpecularDesc =
      in.screenImage(VK_FORMAT_R32_SFLOAT, "sum of the light-table estimates' specular lobes' luminance");
  if (sampledEstimate(in)) {
    push.accumulate = 1;
    const HistoryDecision d = keepHistory(graph, in, accumulation_[in.pathName], kLightsAccumulation, in.pathName,
                                          {{accum, accumDesc}, {accumSpecular, accumSpecularDesc}});
    push.restart = d.action == HistoryAction::Restart ? 1u : 0u;
  } else {
    accumulation_.erase(in.pathName);
  }
  ComputePass pass(in.device, "lights.direct", shaderFor("lights", traced, mapped));
  addTableInputs(pass, structures, tlasHandle, traced, mapped);
  pass.sampled(shared::kLightsPassBaseColor, gbuffer::kBaseColor)
      .optionalStorageInOut(shared::kLightsPassAccum, graph::ImageName{accum},
                            push.accumulate != 0)  // the shader tests push.accumulate
      .optionalStorageInOut(shared::kLightsPassAccumSpecular, graph::ImageName{accumSpecular}, push.accumulate != 0)
      .storageOut(shared::kLightsPassOutput, kLightsRadiance,
                  in.screenImage(VK_FORMAT_R16G16B16A16_SFLOAT,
                                 traced   ? "radiance from the light table (rgb), its specular lobes' luminance (a); "
                                            "ray-traced shadows"
                                 : mapped ? "radiance from the light table (rgb), its specular lobes' luminance (a); "
                                            "shadow-mapped point and spot lights"
                                          : "radiance from the light table (rgb), its specular lobes' luminance (a); "
                                            "unshadowed"))
      .push(push)
      .dispatch(w, h)
      .add(graph);
  return std::string(kLightsRadiance);
}

// The same picks and shadow rays, summed into the I-buffer's four sums of light instead of
// radiance (shaders/common/ibuffer_lights.glsl), each accumulated like the radiance.
void LightsPass::addIbufferRefine(graph::RenderGraph& graph, FrameInputs& in, const std::vector<std::string>& structures,
                                  VkAccelerationStructureKHR tlasHandle) {
  addIbuffer(graph, in, structures, tlasHandle, shared::kIbufferStageRefine);
}

std::string LightsPass::addIbuffer(graph::RenderGraph& graph, FrameInputs& in, const std::vector<std::string>& structures,
                                   VkAccelerationStructureKHR tlasHandle, uint32_t stage) {
  constexpr uint32_t kOut[4] = {shared::kIbufferOutDg, shared::kIbufferOutSg1, shared::kIbufferOutSg2, shared::kIbufferOutMs};
  constexpr uint32_t kAccum[4] = {shared::kIbufferAccumDg, shared::kIbufferAccumSg1, shared::kIbufferAccumSg2,
                                  shared::kIbufferAccumMs};
  const bool traced = !structures.empty() && tlasHandle != VK_NULL_HANDLE;
  const bool mapped = !traced && in.lightShadowViews > 0;
  const uint32_t w = in.settings.width, h = in.settings.height;
  const uint32_t pattern = shared::tlIbufferPattern(in.settings.redeferredRate);
  const bool refine = stage == shared::kIbufferStageRefine;
  shared::LightsPush push{};
  std::array<std::string, 4> accum;
  // lights.accum.<path>.Ldg ...: the suffix of ibuffer.Ldg ...
  // The refining run keeps its own sums (one writer per image): lights.accum.<path>.refine.Ldg ...
  for (size_t q = 0; q < accum.size(); ++q)
    accum[q] = "lights.accum." + in.pathName + (refine ? ".refine" : "") +
               std::string(kIbuffer[q]).substr(std::string_view("ibuffer").size());
  const auto& outputs = refine ? kLightsRefined : kLightsIbuffer;
  const auto accumDesc = in.screenImage(VK_FORMAT_R32G32B32A32_SFLOAT,
                                        "sum of estimates of an I-buffer sum of light (rgb) and their count (a)");
  // One sum per pattern: another pattern's sums hold other pixels' estimates.
  const std::string keeper = in.pathName + ".ibuffer." + std::to_string(pattern);
  for (uint32_t other = shared::kIbufferPatternEvery; other <= shared::kIbufferPatternBlocks; ++other)
    if (other != pattern) accumulation_.erase(in.pathName + ".ibuffer." + std::to_string(other));
  if (refine) {
    push = ibufferPush_;  // the same sums, restarted or not, as this frame's pattern run
    if (push.accumulate) {
      bool stored = true;
      for (const auto& a : accum) stored = stored && in.historyValid(a, accumDesc);
      if (!stored) push.restart = 1;  // its images are new: nothing to add to
      for (const auto& a : accum) graph.declarePersistent(a, accumDesc);
    }
  } else if (sampledEstimate(in)) {
    push.accumulate = 1;
    std::vector<HistoryResource> sums;
    for (const auto& a : accum) sums.push_back({a, accumDesc});
    const HistoryDecision d = keepHistory(graph, in, accumulation_[keeper], kLightsAccumulation, in.pathName, sums);
    push.restart = d.action == HistoryAction::Restart ? 1u : 0u;
  } else {
    accumulation_.erase(keeper);
  }
  push.ibufferStage = stage;
  push.ibufferPattern = pattern;
  if (!refine) ibufferPush_ = push;
  ComputePass pass(in.device, refine ? "lights.direct.refine" : "lights.direct", shaderFor("ibuffer_lights", traced, mapped));
  addTableInputs(pass, structures, tlasHandle, traced, mapped);
  // Outside the refining run the shader reads no mask (shaders/common/ibuffer_stage.glsl).
  pass.optionalSampled(shared::kIbufferRefineMaskSampled, kIbufferRefine, refine);
  for (size_t q = 0; q < kLightsIbuffer.size(); ++q)
    pass.optionalStorageInOut(kAccum[q], graph::ImageName{accum[q]}, push.accumulate != 0)
        .storageOut(kOut[q], outputs[q],
                    in.screenImage(VK_FORMAT_R32G32B32A32_SFLOAT, std::string("the light table's share of ") +
                                                                      std::string(kIbuffer[q]) + ", " +
                                                                      (traced   ? "ray-traced shadows"
                                                                       : mapped ? "shadow-mapped point and spot lights"
                                                                                : "unshadowed"))
                        .decodedAs(ibufferDecoder(q)));
  const glm::uvec2 grid = stage == shared::kIbufferStagePattern ? shared::tlIbufferPatternGrid(glm::uvec2(w, h), pattern)
                                                                : glm::uvec2(w, h);
  pass.push(push).dispatch(grid.x, grid.y).add(graph);
  return std::string(kLightsIbuffer[0]);
}

}  // namespace tl::lighting
