// Step 3 of the Wijgerse (2007) boundary generator: threshold method 4, the fill-ratio threshold that
// must lie above the highest rim value (spec wijgerse-boundary.md §4, thesis §3.3 and §5.2.3).
#pragma once

#include <cstdint>

#include "urbanvec/core/grid.hpp"

namespace urbanvec::boundary {

struct FillThresholdOptions {
  /// Minimum share of the image's pixels to fill, strictly between 0 and 1 (thesis: 0.20-0.40 recommended).
  double minimumFill = 0.28;
  /// Histogram bins over the image's value range used to find the fill-ratio threshold T2 (thesis: 1024).
  int histogramBins = 1024;
};

struct FillThreshold {
  double rimMaximum = 0.0;  ///< T1: the highest value on the image rim
  double threshold =
      0.0;                ///< T2: the highest bin edge whose bins above it hold at least the requested pixels
  double binWidth = 0.0;  ///< the histogram's value range / bins
  int thresholdBin = 0;   ///< index of the last bin used
  std::int64_t thresholdBinCount = 0;  ///< pixels in that bin
  /// Method 4 succeeds only when T2 > T1: otherwise the rim would be filled and the thesis regenerates.
  bool aboveRim = false;
};

/// Finds T1 and T2 of an image (values from radialTransform). Throws InvalidOption on a fill outside (0, 1).
FillThreshold fillThreshold(const Grid<float>& image, const FillThresholdOptions& options);

/// Pixels strictly above `threshold` become 1, the rest 0 (the thesis leaves equality open; §4.1 [INF]).
Grid<std::uint8_t> applyThreshold(const Grid<float>& image, double threshold);

}  // namespace urbanvec::boundary
