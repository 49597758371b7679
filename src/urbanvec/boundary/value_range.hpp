// Smallest and largest value of an image, shared by the radial transform and the fill threshold.
#pragma once

#include <algorithm>
#include <utility>
#include <vector>

namespace urbanvec::boundary {

/// {min, max} of the values ({0, 0} when empty). Eight running minima and maxima instead of one, so the
/// comparisons do not wait for each other (std::minmax_element also branches on every value). The
/// order does not change the result: the images hold no NaN, and no -0 that could tie with +0.
inline std::pair<float, float> valueRange(const std::vector<float>& values) {
  if (values.empty()) return {0.0f, 0.0f};
  constexpr size_t kChains = 8;
  float lo[kChains];
  float hi[kChains];
  std::fill(lo, lo + kChains, values[0]);
  std::fill(hi, hi + kChains, values[0]);
  const size_t n = values.size();
  size_t i = 0;
  for (; i + kChains <= n; i += kChains)
    for (size_t k = 0; k < kChains; ++k) {
      lo[k] = std::min(lo[k], values[i + k]);
      hi[k] = std::max(hi[k], values[i + k]);
    }
  for (; i < n; ++i) {
    lo[0] = std::min(lo[0], values[i]);
    hi[0] = std::max(hi[0], values[i]);
  }
  for (size_t k = 1; k < kChains; ++k) {
    lo[0] = std::min(lo[0], lo[k]);
    hi[0] = std::max(hi[0], hi[k]);
  }
  return {lo[0], hi[0]};
}

}  // namespace urbanvec::boundary
