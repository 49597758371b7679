// Step 2 of the Wijgerse (2007) boundary generator: the radial "slope" transformation that keeps high
// values near the centre so one coherent island survives the threshold (spec wijgerse-boundary.md §3,
// thesis Eq. 3.1).
#pragma once

#include "urbanvec/core/grid.hpp"

namespace urbanvec::boundary {

struct RadialTransformOptions {
  /// Shape n of the slope 1 - D^n: 1 is a linear cone, 2 a quadratic dome (the only values the thesis
  /// tested; any positive value works).
  double slopeExponent = 1.0;
  /// Weight c2 of the Perlin noise ("Perlin mix-in factor"), in [0, 1]. The slope weight is c1 = 1 - c2:
  /// the thesis only reports c2, and only the ratio c2/c1 matters (spec §3 [INF]).
  double noiseWeight = 0.38;
};

/// O = (c1 (1 - D^n) + c2 I) / (c1 + c2), with I the noise min/max-normalised to [0, 1] and D the
/// distance of the pixel centre to the image centre, 1 at the edge midpoints and capped at 1.
/// Returns values in [0, 1].
Grid<float> radialTransform(const Grid<float>& noise, const RadialTransformOptions& options);

}  // namespace urbanvec::boundary
