// The editor's display pass: the final image, or any resource of the frame made visible
// (floats over a range, one channel or all, false colour, invalid values highlighted;
// integers as a colour per value; a slice of a 3D image), zoomed with a texel grid, with
// the selected instance outlined; and an A/B copy of a resource to compare against later.
// Only the editor adds it; headless renders never pay for it.
#pragma once

#include "gpu/pipeline.h"
#include "graph/graph.h"
#include "lighting/common/frame_inputs.h"

#include <optional>
#include <string>
#include <vector>

namespace tl::lighting {

inline constexpr graph::ImageName kDisplayLdr{"display.ldr"};
inline constexpr graph::ImageName kDisplayCopy{"display.copyB"};  // the A/B copy (a cache resource)

struct DisplayRequest {
  std::string source;             // a resource of the frame; empty: the final image
  uint32_t selectedInstance = 0;  // instance index + 1 to outline, 0 for none
  float rangeMin = 0.0f;          // float resources: shown black ...
  float rangeMax = 1.0f;          // ... and white (or the false-colour ends)
  uint32_t channel = 0;           // shared/display.h kDisplayChannel*
  bool falseColour = false;
  bool highlightInvalid = false;  // NaN, infinity, negative
  bool negativesValid = false;    // with highlightInvalid: negatives are data (decoders.h negativesInvalid)
  glm::vec4 window{0.0f, 0.0f, 1.0f, 1.0f};  // the source's UV rectangle shown (zoom and pan)
  uint32_t slice = 0;             // 3D sources: which z slice
  bool keepCopy = false;          // this frame: copy the source to display.copyB ("B")
  bool showCopy = false;          // show display.copyB instead of the source
  // What the source means instead of its stored values (shared/display.h kDisplayMeaning*,
  // decoders.h meaningView), with the resources that meaning reads beside it (A, B). A
  // companion the frame does not hold shows the stored values instead.
  uint32_t meaning = 0;
  std::vector<std::string> companions;
};

class DisplayPass {
 public:
  void add(graph::RenderGraph& graph, FrameInputs& in, const DisplayRequest& request);
  // Without a frame: a viewer of captured images (w x h: the display's size).
  void add(graph::RenderGraph& graph, gpu::Device& device, uint32_t w, uint32_t h, const DisplayRequest& request);

 private:
  std::optional<graph::ResourceDesc> copyDesc_;  // what display.copyB holds, once kept
};

}  // namespace tl::lighting
