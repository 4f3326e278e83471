#include "window_redraw.h"

#include "scene/scene.h"

#include <imgui.h>

namespace tl::editor {
namespace {

template <typename T>
uint64_t mix(uint64_t seed, const T& value) {
  return scene::hashBytes(&value, sizeof value, seed);
}

}  // namespace

uint64_t drawDataHash(const ImDrawData& data) {
  uint64_t h = mix(0, data.Valid);
  h = mix(h, data.DisplayPos), h = mix(h, data.DisplaySize), h = mix(h, data.FramebufferScale);
  for (int l = 0; l < data.CmdListsCount; ++l) {
    const ImDrawList& list = *data.CmdLists[l];
    h = scene::hashBytes(list.VtxBuffer.Data, size_t(list.VtxBuffer.Size) * sizeof(ImDrawVert), h);
    h = scene::hashBytes(list.IdxBuffer.Data, size_t(list.IdxBuffer.Size) * sizeof(ImDrawIdx), h);
    for (const ImDrawCmd& c : list.CmdBuffer) {
      // Field by field: the struct's padding bytes are not initialised.
      h = mix(h, c.ClipRect), h = mix(h, c.TextureId), h = mix(h, c.VtxOffset), h = mix(h, c.IdxOffset);
      h = mix(h, c.ElemCount), h = mix(h, c.UserCallback), h = mix(h, c.UserCallbackData);
    }
  }
  return h;
}

void WindowRedraw::observe(uint64_t drawHash) {
  if (!any_ || drawHash != last_) pending_ = true;
  last_ = drawHash, any_ = true;
}

}  // namespace tl::editor
