// What a furnace test reads from an image (every pixel should be exactly 1) and the mean of a
// few frames of an image (and its luminance), shared by the white furnace (test_furnace.cpp)
// and the reflection tests (test_reflections.cpp).
#pragma once

#include "gpu_fixture.h"
#include "shared/common.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace tl::test {

struct FurnaceStats {
  double mean = 0.0, p99 = 0.0, worst = 0.0;  // of the value; p99 and worst of |value - 1|
  double lowest = 1.0, highest = 1.0;
  size_t nonFinite = 0, values = 0;
};

inline FurnaceStats furnaceStats(const std::vector<float>& t, uint32_t c) {
  FurnaceStats st;
  std::vector<double> deviation;
  for (size_t i = 0; i < t.size() / c; ++i)
    for (uint32_t k = 0; k < std::min(c, 3u); ++k) {
      const double v = t[i * c + k];
      if (!std::isfinite(v)) {
        ++st.nonFinite;
        continue;
      }
      st.mean += v;
      st.lowest = std::min(st.lowest, v), st.highest = std::max(st.highest, v);
      deviation.push_back(std::abs(v - 1.0));
    }
  st.values = deviation.size();
  st.mean /= double(std::max<size_t>(1, st.values));
  std::sort(deviation.begin(), deviation.end());
  if (!deviation.empty()) {
    st.p99 = deviation[std::min(deviation.size() - 1, size_t(0.99 * double(deviation.size())))];
    st.worst = deviation.back();
  }
  return st;
}

// The mean of `averaged` successive frames of `image` (after whatever the session rendered
// before); `channels` receives the image's channel count.
inline std::vector<float> averagedFrames(session::Session& s, std::string_view image, uint32_t averaged, uint32_t& channels) {
  std::vector<float> mean;
  for (uint32_t f = 0; f < averaged; ++f) {
    s.requestBuffer(image);
    s.renderFrames(1);
    auto t = s.buffer(image).texels();
    channels = s.buffer(image).channels();
    mean.resize(t.size(), 0.0f);
    for (size_t i = 0; i < t.size(); ++i) mean[i] += t[i] / float(averaged);
  }
  return mean;
}

// The luminance (shared tlLuminance) of every texel of an image with `channels` channels.
inline std::vector<double> luminanceOf(const std::vector<float>& texels, uint32_t channels) {
  std::vector<double> y(texels.size() / channels);
  for (size_t i = 0; i < y.size(); ++i)
    y[i] = shared::tlLuminance(glm::vec3(texels[i * channels], texels[i * channels + 1], texels[i * channels + 2]));
  return y;
}

// The luminance of the mean of `averaged` successive frames of `image` (averagedFrames).
inline std::vector<double> averagedLuminance(session::Session& s, std::string_view image, uint32_t averaged) {
  uint32_t channels = 0;
  const std::vector<float> mean = averagedFrames(s, image, averaged, channels);  // sets channels
  return luminanceOf(mean, channels);
}

}  // namespace tl::test
