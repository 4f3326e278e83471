#include "buffer_viewer.h"

#include "gpu/formats.h"
#include "shared/common.h"
#include "shared/display.h"

#include <algorithm>
#include <cmath>

namespace tl::editor {

glm::vec4 viewerWindow(const ViewerState& v) {
  const float base = 1.0f / std::max(v.zoom, 1e-3f);
  const float a = std::isfinite(v.aspect) && v.aspect > 0.0f ? v.aspect : 1.0f;
  const glm::vec2 size = base * (a >= 1.0f ? glm::vec2(1.0f, a) : glm::vec2(1.0f / a, 1.0f));
  return glm::vec4(v.centre - 0.5f * size, size);
}

float viewerAspect(uint32_t w, uint32_t h, const glm::vec2& viewport) {
  if (w == 0 || h == 0 || !(viewport.x > 0.0f) || !(viewport.y > 0.0f)) return 1.0f;
  return (float(w) / float(h)) / (viewport.x / viewport.y);
}

std::optional<lighting::MeaningView> shownMeaning(const ViewerState& v, const std::string& decoder) {
  if (!v.meaning) return std::nullopt;
  return lighting::meaningView(decoder);
}

lighting::DisplayRequest displayRequest(const ViewerState& v, const std::string& hoverPreview, VkFormat hoverFormat,
                                        float exposureScale, const std::string& decoder, VkFormat format) {
  lighting::DisplayRequest d;
  if (!hoverPreview.empty()) {
    // A glance while hovering a pass: [0, 1] for normalised formats, the exposure for HDR.
    const gpu::TexelKind kind = gpu::formatInfo(hoverFormat).kind;
    d.source = hoverPreview;
    d.rangeMax = kind == gpu::TexelKind::Float ? 1.0f / exposureScale : 1.0f;
    return d;
  }
  d.source = v.resource;
  d.rangeMin = v.rangeMin;
  d.rangeMax = v.rangeMax;
  d.channel = v.channel;
  d.falseColour = v.falseColour && v.channel != shared::kDisplayChannelRgb;
  d.highlightInvalid = v.highlightInvalid;
  d.negativesValid = !lighting::negativesInvalid(decoder, format);
  if (auto m = shownMeaning(v, decoder)) d.meaning = m->meaning, d.companions = m->companions, d.falseColour = false;
  d.window = viewerWindow(v);
  d.slice = v.slice;
  d.keepCopy = v.keepCopy;
  d.showCopy = v.showCopy && v.copyOf == v.resource;
  return d;
}

std::optional<ProbeLines> probeTexel(const ViewerState& v, const std::string& decoder, const glm::uvec3& t,
                                     const scene::Scene* scene) {
  auto it = v.readbacks.find(v.resource);
  if (it == v.readbacks.end()) return std::nullopt;
  lighting::DecodeInput in{it->second, t.x, t.y, t.z,
                           [&](const std::string& name) -> const graph::Readback* {
                             auto c = v.readbacks.find(name);
                             return c == v.readbacks.end() ? nullptr : &c->second;
                           },
                           scene};
  return ProbeLines{lighting::rawTexel(it->second, t.x, t.y, t.z), lighting::decodeTexel(decoder, in)};
}

std::vector<float> channelValues(const graph::Readback& r, uint32_t channel, uint32_t slice) {
  const gpu::FormatInfo fi = gpu::formatInfo(r.format);
  if (fi.bytes == 0 || fi.channels == 0) return {};
  const size_t plane = size_t(r.extent.width) * r.extent.height;
  const size_t first = std::min<size_t>(slice, std::max(1u, r.extent.depth) - 1) * plane;
  if ((first + plane) * fi.bytes > r.bytes.size()) return {};
  const std::vector<float> t = gpu::decodeTexels(
      r.format, std::span<const uint8_t>(r.bytes.data() + first * fi.bytes, plane * fi.bytes));
  const uint32_t n = fi.channels;
  std::vector<float> out(plane);
  for (size_t i = 0; i < plane; ++i) {
    const float* c = &t[i * n];
    auto at = [&](uint32_t k) { return k < n ? c[k] : (k == 3 ? 1.0f : 0.0f); };
    switch (channel) {
      case shared::kDisplayChannelR: out[i] = at(0); break;
      case shared::kDisplayChannelG: out[i] = at(1); break;
      case shared::kDisplayChannelB: out[i] = at(2); break;
      case shared::kDisplayChannelA: out[i] = at(3); break;
      case shared::kDisplayChannelLuminance:
        out[i] = n == 1 ? at(0) : shared::tlLuminance(glm::vec3(at(0), at(1), at(2)));
        break;
      default: out[i] = n == 1 ? at(0) : std::max({at(0), at(1), at(2)}); break;  // RGB: the brightest channel
    }
  }
  return out;
}

std::optional<std::pair<float, float>> fitRange(std::vector<float> values) {
  values.erase(std::remove_if(values.begin(), values.end(), [](float v) { return !std::isfinite(v); }), values.end());
  if (std::all_of(values.begin(), values.end(), [](float v) { return v == 0.0f; })) return std::nullopt;
  auto at = [&](double q) {
    size_t k = std::min(values.size() - 1, size_t(q * double(values.size() - 1)));
    std::nth_element(values.begin(), values.begin() + k, values.end());
    return values[k];
  };
  float lo = at(0.001), hi = at(0.999);
  if (lo > 0.0f && lo < 0.1f * hi) lo = 0.0f;  // start at black when the data nearly does
  if (!(hi > lo)) {
    const float pad = std::max(std::abs(lo) * 0.5f, 1e-6f);
    lo -= pad, hi += pad;
  }
  return std::pair{lo, hi};
}

std::vector<float> histogram(const std::vector<float>& values, float lo, float hi, int bins) {
  std::vector<float> h(size_t(std::max(bins, 1)), 0.0f);
  const float scale = hi > lo ? float(bins) / (hi - lo) : 0.0f;
  for (float v : values) {
    if (!std::isfinite(v)) continue;
    int b = int((v - lo) * scale);
    h[size_t(std::clamp(b, 0, bins - 1))] += 1.0f;
  }
  return h;
}

}  // namespace tl::editor
