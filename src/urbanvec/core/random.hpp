// Seeded randomness (CONVENTIONS.md "Library shape"): one generator is passed down explicitly, and
// work split across threads derives a per-item seed from the run seed so output is thread-independent.
#pragma once

#include <cstdint>
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

}  // namespace urbanvec
