// Layered 2-D Perlin noise, spec wijgerse-boundary.md §2.1-§2.3.
#include "urbanvec/boundary/perlin_noise.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "urbanvec/core/error.hpp"

namespace urbanvec::boundary {

int maxLayerFor(int size) {
  int layer = 0;
  while ((2LL << layer) <= size) ++layer;
  return layer;
}

namespace {

/// Where one output coordinate falls in a layer of `cells` values: the two neighbouring layer samples
/// and the weight of the second. Samples sit at layer pixel centres (thesis Fig. 5.3); outside the
/// outermost centres the border value is held (clamp), since the thesis does not say (§2.3 [INF]).
struct Tap {
  int lo = 0;
  int hi = 0;
  float weight = 0.0f;
};

std::vector<Tap> tapsFor(int size, int cells) {
  std::vector<Tap> taps(static_cast<size_t>(size));
  for (int i = 0; i < size; ++i) {
    const double u = (i + 0.5) / size * cells - 0.5;
    const double clamped = std::clamp(u, 0.0, static_cast<double>(cells - 1));
    Tap& t = taps[static_cast<size_t>(i)];
    t.lo = static_cast<int>(std::floor(clamped));
    t.hi = std::min(t.lo + 1, cells - 1);
    t.weight = static_cast<float>(clamped - t.lo);
  }
  return taps;
}

}  // namespace

Grid<float> perlinNoise(const PerlinOptions& options, PerlinSeed seed) {
  const int size = options.size;
  if (size < 16)
    throw invalidOption("the image size (-size) must be at least 16 pixels, got " + std::to_string(size));
  const int maxLayer = maxLayerFor(size);
  if (options.startLayer < 0 || options.endLayer > maxLayer || options.startLayer > options.endLayer)
    throw invalidOption("the Perlin layers (-layers) must satisfy 0 <= start <= end <= " +
                        std::to_string(maxLayer) + " (log2 of the size " + std::to_string(size) + "), got " +
                        std::to_string(options.startLayer) + "-" + std::to_string(options.endLayer));

  if (!(options.persistence > 0.0) || !std::isfinite(options.persistence))
    throw invalidOption("the Perlin persistence (-persistence) must be positive, got " +
                        std::to_string(options.persistence));
  std::mt19937 generator(seed);
  // Highest-order bits only (thesis §2.5.5 "Bad ideas"): 24 bits fill a float mantissa exactly.
  const float toRange = 255.0f / 16777216.0f;
  Grid<float> noise(size, size, 0.0f);
  double weightSum = 0.0;
  for (int layer = options.startLayer; layer <= options.endLayer; ++layer) {
    const int cells = 1 << layer;
    Grid<float> values(cells, cells);
    for (float& v : values.cells) v = static_cast<float>(generator() >> 8) * toRange;
    // p(k) = (1/2)^(k+1) (Eq. 2.23) for persistence 0.5; only the ratio between layers
    // matters after normalising, so k may be the absolute layer number.
    const double weight = std::pow(options.persistence, layer + 1);
    weightSum += weight;
    const std::vector<Tap> taps = tapsFor(size, cells);
    const float w = static_cast<float>(weight);
    // Separable bilinear sampling: widen every layer row to the output width once, then blend two
    // widened rows per output row (a contiguous loop the compiler vectorises).
    Grid<float> widened(size, cells);
    for (int row = 0; row < cells; ++row) {
      const float* in = &values.at(0, row);
      float* out = &widened.at(0, row);
      for (int x = 0; x < size; ++x) {
        const Tap& tx = taps[static_cast<size_t>(x)];
        out[x] = in[tx.lo] + (in[tx.hi] - in[tx.lo]) * tx.weight;
      }
    }
    for (int y = 0; y < size; ++y) {
      const Tap& ty = taps[static_cast<size_t>(y)];
      const float* lo = &widened.at(0, ty.lo);
      const float* hi = &widened.at(0, ty.hi);
      const float wy = ty.weight;
      float* out = &noise.at(0, y);
      for (int x = 0; x < size; ++x) out[x] += w * (lo[x] + (hi[x] - lo[x]) * wy);
    }
  }
  const float scale = static_cast<float>(1.0 / weightSum);
  for (float& v : noise.cells) v *= scale;
  return noise;
}

}  // namespace urbanvec::boundary
