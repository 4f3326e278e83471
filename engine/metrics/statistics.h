// Order statistics of a list of measurements (GPU milliseconds per frame or per pass): the
// median and the quantiles bench and compare report.
#pragma once

#include <algorithm>
#include <utility>
#include <vector>

namespace tl::metrics {

// The q-quantile (0 = the least, 1 = the greatest) of `v`, interpolated linearly between the
// two nearest ranks; 0 for an empty list.
inline double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double pos = q * double(v.size() - 1);
  const size_t i = size_t(pos);
  const double f = pos - double(i);
  return i + 1 < v.size() ? v[i] * (1.0 - f) + v[i + 1] * f : v[i];
}

// The middle value (the mean of the two middle ones for an even count); 0 for an empty list.
inline double median(std::vector<double> v) { return quantile(std::move(v), 0.5); }

}  // namespace tl::metrics
