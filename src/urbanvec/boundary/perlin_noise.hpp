// Step 1 of the Wijgerse (2007) boundary generator: layered two-dimensional Perlin noise
// (spec wijgerse-boundary.md §2, thesis §2.4 and §5.2.3).
#pragma once

#include <cstdint>

#include "urbanvec/core/grid.hpp"

namespace urbanvec::boundary {

struct PerlinOptions {
  /// Width and height of the square output image, in pixels (thesis: 512 in every experiment).
  int size = 512;
  /// Coarsest layer; layer l is a grid of 2^l x 2^l random values (thesis §4.2.2: 2 is the first
  /// significant layer, 0 only adds a constant).
  int startLayer = 3;
  /// Finest layer, at most log2(size) (layer 9 is 512 x 512).
  int endLayer = 9;
  /// Weight ratio between a layer and the next coarser one. The thesis's Eq. 2.23,
  /// p(k) = (1/2)^(k+1), reads as 0.5, but that noise is too smooth: its hulls measure D_R = 1.11 and
  /// 0.3 % of the thesis's recommended cases are valid. 0.7 gives the thesis's hull statistics
  /// (l0 = 1.59, mean ln r = 2.54 against 1.582 and 2.533 in Table 4.1) and the most valid cases
  /// (docs/boundary.md, bench/boundary/README.md).
  double persistence = 0.7;
};

/// The thesis's generator is the original MT19937 with a 32-bit seed (§2.5.5, §5.2.3), one instance per
/// run, so a seed fully determines the image.
using PerlinSeed = std::uint32_t;

/// Fills layers startLayer..endLayer with uniform values in [0, 255) drawn from MT19937(seed) (layer by
/// layer, row-major, taking the 24 highest bits of each draw as the thesis asks), samples every layer
/// bilinearly at each output pixel centre and returns the weighted sum, weights persistence^(l+1)
/// (Eq. 2.23: halving per finer layer), divided by the sum of the weights: values in [0, 255].
/// Throws InvalidOption when the layer range does not fit the size.
Grid<float> perlinNoise(const PerlinOptions& options, PerlinSeed seed);

/// Largest meaningful layer for an image size: floor(log2(size)).
int maxLayerFor(int size);

}  // namespace urbanvec::boundary
