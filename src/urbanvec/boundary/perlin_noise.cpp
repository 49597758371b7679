// Layered 2-D Perlin noise, spec wijgerse-boundary.md §2.1-§2.3.
#include "urbanvec/boundary/perlin_noise.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
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

/// MT19937, the standard 32-bit Mersenne Twister: the same numbers as std::mt19937 with the same seed
/// (unit test PerlinNoise.RandomGridIsTheMersenneTwisterSequence), produced in blocks. Twist and
/// tempering are plain loops over the 624-word state that the compiler vectorises; std::mt19937
/// tempers one number per call, and its draws were half of this stage's instructions.
class MersenneTwister {
 public:
  explicit MersenneTwister(std::uint32_t seed) {
    state_[0] = seed;
    for (std::uint32_t i = 1; i < kN; ++i)
      state_[i] = 1812433253u * (state_[i - 1] ^ (state_[i - 1] >> 30)) + i;
  }

  /// Writes the next `count` numbers to `out`.
  void generate(std::uint32_t* out, size_t count) {
    while (count > 0) {
      if (next_ == kN) twist();
      const size_t n = std::min(count, kN - next_);
      const std::uint32_t* from = state_ + next_;
      for (size_t i = 0; i < n; ++i) {
        std::uint32_t y = from[i];
        y ^= y >> 11;
        y ^= (y << 7) & 0x9d2c5680u;
        y ^= (y << 15) & 0xefc60000u;
        out[i] = y ^ (y >> 18);
      }
      next_ += n;
      out += n;
      count -= n;
    }
  }

 private:
  static constexpr size_t kN = 624;
  static constexpr size_t kM = 397;

  static std::uint32_t next(std::uint32_t upper, std::uint32_t lower, std::uint32_t far) {
    const std::uint32_t y = (upper & 0x80000000u) | (lower & 0x7fffffffu);
    return far ^ (y >> 1) ^ ((0u - (y & 1u)) & 0x9908b0dfu);
  }

  void twist() {
    for (size_t i = 0; i < kN - kM; ++i) state_[i] = next(state_[i], state_[i + 1], state_[i + kM]);
    for (size_t i = kN - kM; i < kN - 1; ++i) state_[i] = next(state_[i], state_[i + 1], state_[i + kM - kN]);
    state_[kN - 1] = next(state_[kN - 1], state_[0], state_[kM - 1]);
    next_ = 0;
  }

  std::uint32_t state_[kN];
  size_t next_ = kN;
};

/// One layer's random grid, resampled to the output width row by row as the output rows need them.
class Layer {
 public:
  Layer(int size, int cells, const float* values, float weight)
      : size_(size), cells_(cells), values_(values), weight_(weight), taps_(tapsFor(size, cells)) {
    identity_ = cells == size;
    for (int x = 0; x < size && identity_; ++x) {
      const Tap& t = taps_[static_cast<size_t>(x)];
      identity_ = t.lo == x && t.weight == 0.0f;
    }
    if (!identity_)
      for (int slot = 0; slot < 2; ++slot) widened_[slot].resize(static_cast<size_t>(size));
  }

  /// Adds this layer's weighted bilinear sample at every pixel of output row y to `row`.
  void addRow(int y, float* row) {
    const Tap& ty = taps_[static_cast<size_t>(y)];
    const float* lo = widenedRow(ty.lo);
    const float* hi = widenedRow(ty.hi);
    const float wy = ty.weight;
    const float w = weight_;
    for (int x = 0; x < size_; ++x) row[x] += w * (lo[x] + (hi[x] - lo[x]) * wy);
  }

 private:
  /// Layer row `row` sampled at every output column. Separable bilinear sampling: each layer row is
  /// widened once, when the first output row needs it; rows lo and lo + 1 never share a slot.
  const float* widenedRow(int row) {
    const float* in = values_ + static_cast<size_t>(row) * static_cast<size_t>(cells_);
    // A layer as fine as the output samples each value at its own centre: a + (b - a) * 0 == a.
    if (identity_) return in;
    const int slot = row & 1;
    float* out = widened_[slot].data();
    if (widenedIndex_[slot] != row) {
      for (int x = 0; x < size_; ++x) {
        const Tap& tx = taps_[static_cast<size_t>(x)];
        out[x] = in[tx.lo] + (in[tx.hi] - in[tx.lo]) * tx.weight;
      }
      widenedIndex_[slot] = row;
    }
    return out;
  }

  int size_;
  int cells_;
  const float* values_;
  float weight_;
  std::vector<Tap> taps_;
  bool identity_ = false;
  std::vector<float> widened_[2];
  int widenedIndex_[2] = {-1, -1};
};

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
  // Highest-order bits only (thesis §2.5.5 "Bad ideas"): 24 bits fill a float mantissa exactly.
  const float toRange = 255.0f / 16777216.0f;
  // All layers' random values first, in the generator's order (layer by layer, row-major).
  size_t total = 0;
  for (int layer = options.startLayer; layer <= options.endLayer; ++layer) total += size_t{1} << (2 * layer);
  std::vector<float> values;
  values.reserve(total);
  MersenneTwister generator(seed);
  std::uint32_t draws[1024];
  float converted[std::size(draws)];
  for (size_t done = 0; done < total;) {
    const size_t n = std::min(total - done, std::size(draws));
    generator.generate(draws, n);
    // Below 2^24, so the signed conversion (one SSE2 instruction for four) is exact.
    for (size_t i = 0; i < n; ++i)
      converted[i] = static_cast<float>(static_cast<std::int32_t>(draws[i] >> 8)) * toRange;
    values.insert(values.end(), converted, converted + n);
    done += n;
  }
  std::vector<Layer> layers;
  double weightSum = 0.0;
  size_t offset = 0;
  for (int layer = options.startLayer; layer <= options.endLayer; ++layer) {
    const int cells = 1 << layer;
    // p(k) = (1/2)^(k+1) (Eq. 2.23) for persistence 0.5; only the ratio between layers
    // matters after normalising, so k may be the absolute layer number.
    const double weight = std::pow(options.persistence, layer + 1);
    weightSum += weight;
    layers.emplace_back(size, cells, values.data() + offset, static_cast<float>(weight));
    offset += static_cast<size_t>(cells) * static_cast<size_t>(cells);
  }
  const float scale = static_cast<float>(1.0 / weightSum);
  // Output row by row, every layer added in turn (coarsest first, as a sum over whole layers would),
  // so the row being summed stays in the first-level cache.
  Grid<float> noise;
  noise.width = size;
  noise.height = size;
  noise.cells.reserve(static_cast<size_t>(size) * static_cast<size_t>(size));
  std::vector<float> row(static_cast<size_t>(size));
  for (int y = 0; y < size; ++y) {
    std::fill(row.begin(), row.end(), 0.0f);
    for (Layer& layer : layers) layer.addRow(y, row.data());
    for (float& v : row) v *= scale;
    noise.cells.insert(noise.cells.end(), row.begin(), row.end());
  }
  return noise;
}

}  // namespace urbanvec::boundary
