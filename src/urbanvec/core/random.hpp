// Seeded randomness (CONVENTIONS.md "Library shape"): one generator is passed down explicitly, and
// work split across threads derives a per-item seed from the run seed so output is thread-independent.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

namespace urbanvec {

using Rng = std::mt19937_64;

/// SplitMix64 mixing of (run seed, item index): well-spread, independent streams per item.
inline std::uint64_t deriveSeed(std::uint64_t runSeed, std::uint64_t item) {
  std::uint64_t z = runSeed + 0x9E3779B97F4A7C15ULL * (item + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

/// A uniform draw in [0, 1) for (run seed, item): the top 53 bits of deriveSeed.
inline double unitDraw(std::uint64_t runSeed, std::uint64_t item) {
  return static_cast<double>(deriveSeed(runSeed, item) >> 11) * 0x1p-53;
}

/// std::generate_canonical<double, 53> of libstdc++ (GCC 12) for an engine of 64 random bits, as
/// std::uniform_real_distribution and std::normal_distribution draw it, without its two long double
/// logarithms per draw (-frounding-math keeps GCC from folding them; issue 21): the draw times 2^-64,
/// or the largest double below 1 when that rounds to 1. The same values bit for bit
/// (tests/unit/core: RandomDraws).
template <class Engine>
double canonicalDraw(Engine& engine) {
  static_assert(Engine::min() == 0 && Engine::max() == std::numeric_limits<std::uint64_t>::max(),
                "canonicalDraw needs an engine of 64 random bits");
  const double u = static_cast<double>(engine()) * 0x1p-64;
  return u >= 1.0 ? std::nextafter(1.0, 0.0) : u;
}

/// std::normal_distribution<double>(mean, sigma) as libstdc++ (GCC 12) draws it: Marsaglia's polar
/// method on canonicalDraw, the second value of each pair kept for the next call. The same values bit
/// for bit (tests/unit/core: RandomDraws).
class NormalDraw {
 public:
  NormalDraw(double mean, double sigma) : mean_(mean), sigma_(sigma) {}
  template <class Engine>
  double operator()(Engine& engine) {
    double value;
    if (saved_) {
      saved_ = false;
      value = savedValue_;
    } else {
      double x, y, r2;
      do {
        x = 2.0 * canonicalDraw(engine) - 1.0;
        y = 2.0 * canonicalDraw(engine) - 1.0;
        r2 = x * x + y * y;
      } while (r2 > 1.0 || r2 == 0.0);
      const double mult = std::sqrt(-2 * std::log(r2) / r2);
      savedValue_ = x * mult;
      saved_ = true;
      value = y * mult;
    }
    return value * sigma_ + mean_;
  }

 private:
  double mean_, sigma_;
  double savedValue_ = 0.0;
  bool saved_ = false;
};

}  // namespace urbanvec
