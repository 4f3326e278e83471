// The buffer viewer's state and logic: which resource the viewport shows and how
// (channel, range, false colour, invalid-value highlight, zoom, 3D slice, A/B copy), its
// read-back for the histogram and the pixel probe. The Buffers panel (buffer_panel.cpp)
// draws it; EditorApp turns it into the display request. Nothing here knows a resource by
// name: formats and each resource's declared decoder say how to read it.
#pragma once

#include "graph/executor.h"
#include "session/inspection.h"

#include <glm/glm.hpp>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace tl::editor {

struct ViewerState {
  std::string resource;            // "" = the final image
  uint32_t channel = 0;            // shared/display.h kDisplayChannel*
  float rangeMin = 0.0f, rangeMax = 1.0f;
  bool autoFitPending = true;      // fit the range to the next read-back
  bool falseColour = false;
  bool highlightInvalid = true;
  bool meaning = true;             // what a decoded resource means (decoders.h meaningView), not its values
  float zoom = 1.0f;               // display pixels per source pixel at 1 = the whole image
  glm::vec2 centre{0.5f};          // source UV at the viewport's centre
  // The source's shape against the viewport's, (source w/h) / (viewport w/h): the window is
  // that much taller than wide (or wider, below 1) so texels stay square — a 6:1 voxel
  // clipmap slice is not stretched to the viewport. Set each frame for the viewed resource.
  float aspect = 1.0f;
  uint32_t slice = 0;              // 3D resources
  bool live = true;                // read the resource back every frame (histogram, probe)
  bool refresh = false;            // one read-back when not live
  bool keepCopy = false;           // one frame: store the resource as "B"
  bool showCopy = false;
  std::string copyOf;              // resource "B" holds
  graph::Readback copyReadback;    // and its values, for the A-B statistics
  std::optional<glm::uvec3> probe; // the texel under the cursor
  // The last read-back of the resource and its decoder's companions.
  std::map<std::string, graph::Readback> readbacks;
  // The shown meaning's values over the last read-back (decoders.h meaningValues), computed
  // once per read-back, not per UI frame; empty for stored values or a fixed meaning.
  std::vector<float> meaningValues;
};

// What the probe shows for texel `t` of the viewed resource, from the last read-backs: its
// stored values and what its decoder (with its companions) says. Null when not read back.
struct ProbeLines {
  lighting::DecodedLines raw, decoded;
};
std::optional<ProbeLines> probeTexel(const ViewerState& v, const std::string& decoder, const glm::uvec3& t,
                                     const scene::Scene* scene);

// The display request for the state (`hoverPreview` overrides the resource while a pass is
// hovered in the Timing panel; its range then comes from the format).
// `decoder`, `format`: the viewed resource's (its meaning, which negatives are invalid).
lighting::DisplayRequest displayRequest(const ViewerState& v, const std::string& hoverPreview, VkFormat hoverFormat,
                                        float exposureScale, const std::string& decoder = {},
                                        VkFormat format = VK_FORMAT_UNDEFINED);
// The meaning the viewer shows for a resource with this decoder now (none: its values).
std::optional<lighting::MeaningView> shownMeaning(const ViewerState& v, const std::string& decoder);
// The source UV rectangle shown (offset, size) for a zoom, centre and aspect.
glm::vec4 viewerWindow(const ViewerState& v);
// The aspect (ViewerState::aspect) of a source of w x h texels in a viewport of that size.
float viewerAspect(uint32_t w, uint32_t h, const glm::vec2& viewport);
// Values of the shown channel over the read-back (the slice of a 3D image), as the display
// computes them.
std::vector<float> channelValues(const graph::Readback& r, uint32_t channel, uint32_t slice);
// The range a viewer fits to values: 0.1 and 99.9 percentiles of the finite ones (so a few
// fireflies do not squash everything), widened when flat. None when there is nothing to fit
// (no finite value, or every one zero: a frame with nothing in it yet).
std::optional<std::pair<float, float>> fitRange(std::vector<float> values);
// `bins` counts of values in [lo, hi] (outside ones clamp into the end bins; non-finite skipped).
std::vector<float> histogram(const std::vector<float>& values, float lo, float hi, int bins);

}  // namespace tl::editor
