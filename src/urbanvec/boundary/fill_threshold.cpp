// Threshold method 4, spec wijgerse-boundary.md §4 and §4.1 (thesis §3.3, §5.2.3, Fig. 5.4).
#include "urbanvec/boundary/fill_threshold.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "urbanvec/core/error.hpp"

namespace urbanvec::boundary {

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

  const auto [lowest, highest] = std::minmax_element(image.cells.begin(), image.cells.end());
  const double minimum = *lowest;
  const double range = static_cast<double>(*highest) - minimum;
  const int bins = options.histogramBins;
  result.binWidth = range / bins;
  std::vector<std::int64_t> histogram(static_cast<size_t>(bins), 0);
  if (range > 0.0) {
    const double toBin = bins / range;
    for (float v : image.cells) {
      const int bin = std::min(bins - 1, static_cast<int>((v - minimum) * toBin));
      ++histogram[static_cast<size_t>(bin)];
    }
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
  Grid<std::uint8_t> mask(image.width, image.height, 0);
  for (size_t i = 0; i < image.size(); ++i) mask.cells[i] = image.cells[i] > threshold ? 1 : 0;
  return mask;
}

}  // namespace urbanvec::boundary
