// Hybrid ray-traced sun shadows (GameWorks HRTS; the `hybridShadows` setting): where the
// frame's path has a top level (LightingOutputs::shadowTlasHandle, the rt path's), the pass
// shadow.sun.hybrid (shaders/common/sun_shadow_hybrid.comp) writes the sun's visibility per
// pixel -- the ray's hard shadow near contacts, PCSS over the shadow map further away, blended
// by blocker distance -- and the composite (or redeferred shading's ibuffer.light) takes the
// sun's shadow from it instead of its own PCSS lookup.
#pragma once

#include "graph/graph.h"
#include "lighting/common/frame_inputs.h"
#include "lighting/lighting_path.h"

namespace tl::lighting {

inline constexpr graph::ImageName kShadowSunVisibility{"shadow.sun.visibility"};  // R16F, 0..1

// Adds shadow.sun.hybrid (creating kShadowSunVisibility) where this frame's sun shadow is
// hybrid: the setting on, a sun that casts shadows, a top level from the path to trace
// against, and no alpha cut-out in the scene (the ray cannot test alpha yet: such a scene
// keeps the map). Returns whether it did: then the shading passes read kShadowSunVisibility.
bool addHybridSunShadow(graph::RenderGraph& graph, FrameInputs& in, const LightingOutputs& path);

}  // namespace tl::lighting
