// Step 8Pre of the shrinking pipeline (spec §B.9): the per-pixel energy the seams follow — a blend of
// the inverted grey image and the inverted distance field (high near skeleton elements, low in empty
// areas), with frozen pixels at +infinity.
#pragma once

#include <vector>

#include "urbanvec/shrink/rasterise.hpp"

namespace urbanvec::shrink {

/// Exact squared Euclidean distance (in pixels²) from every pixel to the nearest pixel with
/// `feature` set, by Felzenszwalb & Huttenlocher's two-pass lower-envelope transform, O(width*height).
/// Pixels have +infinity when there is no feature at all.
std::vector<double> squaredDistanceTransform(const std::vector<char>& feature, int width, int height);

/// E = b * ink + (1 - b) * DF with DF = 255 (1 - d / d_max), d the distance to the nearest inked pixel
/// (b = grayDistBalance, [INFERENCE] §B.10); frozen pixels (freezeOwner != kNotFrozen) get +infinity.
std::vector<float> seamEnergy(const SkeletonRaster& raster, double grayDistBalance);

}  // namespace urbanvec::shrink
