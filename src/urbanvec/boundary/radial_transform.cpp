// Radial transformation, spec wijgerse-boundary.md §3 (thesis §3.2, Eq. 3.1, §5.2.3).
#include "urbanvec/boundary/radial_transform.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "urbanvec/boundary/value_range.hpp"
#include "urbanvec/core/error.hpp"

namespace urbanvec::boundary {

Grid<float> radialTransform(const Grid<float>& noise, const RadialTransformOptions& options) {
  if (!(options.noiseWeight >= 0.0 && options.noiseWeight <= 1.0))
    throw invalidOption("the Perlin weight c2 (-c2) must lie between 0 and 1, got " +
                        std::to_string(options.noiseWeight));
  if (!(options.slopeExponent > 0.0) || !std::isfinite(options.slopeExponent))
    throw invalidOption("the slope exponent n (-slope) must be positive, got " +
                        std::to_string(options.slopeExponent));
  const double c2 = options.noiseWeight;
  const double c1 = 1.0 - c2;
  const auto [lowest, highest] = valueRange(noise.cells);
  const double minimum = lowest;
  const double range = static_cast<double>(highest) - minimum;
  // A constant image (a single layer 0) has no noise to normalise: I = 0 everywhere.
  const double toUnit = range > 0.0 ? 1.0 / range : 0.0;

  Grid<float> out(noise.width, noise.height);
  // Centre between the middle pixels and radius = centre-to-edge-midpoint distance (§3 [INF]).
  const double cx = noise.width / 2.0;
  const double cy = noise.height / 2.0;
  const double radius = std::min(cx, cy);
  const double exponent = options.slopeExponent;
  // D^n from the squared distance: the common n = 1 and n = 2 avoid pow().
  auto slopeOf = [exponent](double squared) {
    return exponent == 2.0   ? squared
           : exponent == 1.0 ? std::sqrt(squared)
                             : std::pow(squared, exponent / 2.0);
  };
  const int width = noise.width;
  const int height = noise.height;
  std::vector<double> dx2(static_cast<size_t>(width));
  for (int x = 0; x < width; ++x) {
    const double d = (x + 0.5 - cx) / radius;
    dx2[static_cast<size_t>(x)] = d * d;
  }
  const float noiseScale = static_cast<float>(c2 * toUnit);
  const float noiseOffset = static_cast<float>(-c2 * toUnit * minimum);
  std::vector<float> slopeRow(static_cast<size_t>(width));
  // The slope is symmetric about both centre lines, exactly: x + 0.5 - cx for column x and for column
  // width - 1 - x are exact negatives (multiples of 0.5), and so are their quotients by the radius.
  // So each slope value is computed once for four pixels (the square roots were most of the cost).
  for (int y = 0; y < (height + 1) / 2; ++y) {
    const double dy = (y + 0.5 - cy) / radius;
    for (int x = 0; x < (width + 1) / 2; ++x) {
      const double squared = std::min(1.0, dx2[static_cast<size_t>(x)] + dy * dy);
      const float slope = static_cast<float>(c1 * (1.0 - slopeOf(squared)));
      slopeRow[static_cast<size_t>(x)] = slope;
      slopeRow[static_cast<size_t>(width - 1 - x)] = slope;
    }
    for (const int row : {y, height - 1 - y}) {
      const float* in = &noise.at(0, row);
      float* o = &out.at(0, row);
      // c1 + c2 = 1, so the denominator of Eq. 3.1 drops out.
      for (int x = 0; x < width; ++x)
        o[x] = slopeRow[static_cast<size_t>(x)] + noiseScale * in[x] + noiseOffset;
    }
  }
  return out;
}

}  // namespace urbanvec::boundary
