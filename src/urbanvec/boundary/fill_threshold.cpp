// Threshold method 4, spec wijgerse-boundary.md §4 and §4.1 (thesis §3.3, §5.2.3, Fig. 5.4).
#include "urbanvec/boundary/fill_threshold.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "urbanvec/boundary/value_range.hpp"
#include "urbanvec/core/error.hpp"

namespace urbanvec::boundary {

namespace {

/// The largest float f <= threshold (NaN for NaN): for every float v, v > f exactly when
/// double(v) > threshold, so the mask compares floats with floats, four pixels per instruction.
float largestFloatNotAbove(double threshold) {
  constexpr double kMax = std::numeric_limits<float>::max();
  if (std::isnan(threshold)) return std::numeric_limits<float>::quiet_NaN();
  if (threshold >= kMax)
    return threshold == std::numeric_limits<double>::infinity() ? std::numeric_limits<float>::infinity()
                                                                : std::numeric_limits<float>::max();
  if (threshold < -kMax) return -std::numeric_limits<float>::infinity();
  const float nearest = static_cast<float>(threshold);
  return static_cast<double>(nearest) > threshold
             ? std::nextafter(nearest, -std::numeric_limits<float>::infinity())
             : nearest;
}

}  // namespace

FillThreshold fillThreshold(const Grid<float>& image, const FillThresholdOptions& options) {
  if (!(options.minimumFill > 0.0 && options.minimumFill < 1.0))
    throw invalidOption("the minimum fill ratio (-fill) must lie strictly between 0 and 1, got " +
                        std::to_string(options.minimumFill));
  if (options.histogramBins < 1)
    throw invalidOption("the histogram needs at least one bin, got " + std::to_string(options.histogramBins));
  if (image.width < 2 || image.height < 2) throw invalidInput("the image to threshold is smaller than 2 x 2");
  FillThreshold result;
  float rim = image.at(0, 0);
  for (int x = 0; x < image.width; ++x) rim = std::max({rim, image.at(x, 0), image.at(x, image.height - 1)});
  for (int y = 0; y < image.height; ++y) rim = std::max({rim, image.at(0, y), image.at(image.width - 1, y)});
  result.rimMaximum = rim;

  const auto [lowest, highest] = valueRange(image.cells);
  const double minimum = lowest;
  const double range = static_cast<double>(highest) - minimum;
  const int bins = options.histogramBins;
  result.binWidth = range / bins;
  std::vector<std::int64_t> histogram(static_cast<size_t>(bins), 0);
  if (range > 0.0) {
    const double toBin = bins / range;
    // Neighbouring pixels mostly share a bin: counting them in turn into four histograms keeps each
    // increment from waiting for the previous one.
    constexpr size_t kCopies = 4;
    std::vector<std::int64_t> counts(kCopies * static_cast<size_t>(bins), 0);
    const size_t n = image.size();
    const float* values = image.cells.data();
    auto binOf = [&](float v) {
      return static_cast<size_t>(std::min(bins - 1, static_cast<int>((v - minimum) * toBin)));
    };
    size_t i = 0;
    for (; i + kCopies <= n; i += kCopies)
      for (size_t k = 0; k < kCopies; ++k) ++counts[k * static_cast<size_t>(bins) + binOf(values[i + k])];
    for (; i < n; ++i) ++counts[binOf(values[i])];
    for (size_t k = 0; k < kCopies; ++k)
      for (size_t b = 0; b < static_cast<size_t>(bins); ++b)
        histogram[b] += counts[k * static_cast<size_t>(bins) + b];
  } else {
    histogram[0] = static_cast<std::int64_t>(image.size());
  }
  // Walk down from the highest bin until the requested pixel count is reached (§4.1 step 3).
  double stillToFill = options.minimumFill * static_cast<double>(image.size());
  int bin = bins - 1;
  for (; bin > 0; --bin) {
    stillToFill -= static_cast<double>(histogram[static_cast<size_t>(bin)]);
    if (stillToFill <= 0.0) break;
  }
  result.thresholdBin = bin;
  result.thresholdBinCount = histogram[static_cast<size_t>(bin)];
  // The thesis omits the minimum (values start near 0); adding it keeps the rule exact (§4.1 [INF]).
  result.threshold = minimum + bin * result.binWidth;
  result.aboveRim = result.threshold > result.rimMaximum;
  return result;
}

Grid<std::uint8_t> applyThreshold(const Grid<float>& image, double threshold) {
  const float below = largestFloatNotAbove(threshold);
  Grid<std::uint8_t> mask(image.width, image.height, 0);
  const float* in = image.cells.data();
  std::uint8_t* out = mask.cells.data();
  for (size_t i = 0; i < image.size(); ++i) out[i] = in[i] > below ? 1 : 0;
  return mask;
}

}  // namespace urbanvec::boundary
