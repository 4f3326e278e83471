// A plain float image for the metrics: interleaved channels, row-major, top row first.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace tl::metrics {

struct Image {
  uint32_t width = 0, height = 0, channels = 0;
  std::vector<float> data;

  static Image fromTexels(uint32_t w, uint32_t h, uint32_t c, std::vector<float> texels) {
    if (texels.size() != size_t(w) * h * c) throw std::invalid_argument("image data does not match its size");
    return {w, h, c, std::move(texels)};
  }
  static Image filled(uint32_t w, uint32_t h, uint32_t c, float value) {
    return {w, h, c, std::vector<float>(size_t(w) * h * c, value)};
  }
  float at(uint32_t x, uint32_t y, uint32_t c) const { return data[(size_t(y) * width + x) * channels + c]; }
  float& at(uint32_t x, uint32_t y, uint32_t c) { return data[(size_t(y) * width + x) * channels + c]; }
  size_t pixels() const { return size_t(width) * height; }
};

// A metric's value and its per-pixel map (one channel, the image's size).
struct MetricResult {
  double value = 0.0;
  Image errorMap;
};

}  // namespace tl::metrics
