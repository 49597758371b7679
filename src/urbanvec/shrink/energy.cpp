// Step 8Pre (spec §B.9): energy = blend of inverted grey and an exact Euclidean distance transform
// (the spec's [INFERENCE] replacement of the thesis's per-pixel flood fill), inverted polarity.
#include "urbanvec/shrink/energy.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace urbanvec::shrink {
namespace {

/// 1-D squared distance transform of f (Felzenszwalb & Huttenlocher 2012, algorithm 1).
void transform1d(const double* f, double* d, int n, std::vector<int>& v, std::vector<double>& z) {
  const double inf = std::numeric_limits<double>::infinity();
  int k = -1;
  for (int q = 0; q < n; ++q) {
    if (f[q] == inf) continue;
    while (k >= 0) {
      const int p = v[static_cast<size_t>(k)];
      const double s =
          ((f[q] + q * static_cast<double>(q)) - (f[p] + p * static_cast<double>(p))) / (2.0 * (q - p));
      if (s <= z[static_cast<size_t>(k)]) {
        --k;
        continue;
      }
      ++k;
      v[static_cast<size_t>(k)] = q;
      z[static_cast<size_t>(k)] = s;
      z[static_cast<size_t>(k) + 1] = inf;
      break;
    }
    if (k < 0) {
      k = 0;
      v[0] = q;
      z[0] = -inf;
      z[1] = inf;
    }
  }
  if (k < 0) {
    std::fill(d, d + n, inf);
    return;
  }
  int j = 0;
  for (int q = 0; q < n; ++q) {
    while (z[static_cast<size_t>(j) + 1] < q) ++j;
    const int p = v[static_cast<size_t>(j)];
    d[q] = (q - p) * static_cast<double>(q - p) + f[p];
  }
}

}  // namespace

std::vector<double> squaredDistanceTransform(const std::vector<char>& feature, int width, int height) {
  const double inf = std::numeric_limits<double>::infinity();
  const size_t w = static_cast<size_t>(width), h = static_cast<size_t>(height);
  std::vector<double> grid(w * h);
  for (size_t i = 0; i < grid.size(); ++i) grid[i] = feature[i] ? 0.0 : inf;
  const size_t longest = std::max(w, h);
  std::vector<double> f(longest), d(longest), z(longest + 1);
  std::vector<int> v(longest);
  for (size_t c = 0; c < w; ++c) {  // columns
    for (size_t r = 0; r < h; ++r) f[r] = grid[r * w + c];
    transform1d(f.data(), d.data(), height, v, z);
    for (size_t r = 0; r < h; ++r) grid[r * w + c] = d[r];
  }
  for (size_t r = 0; r < h; ++r) {  // rows
    transform1d(&grid[r * w], d.data(), width, v, z);
    std::copy(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(w),
              grid.begin() + static_cast<std::ptrdiff_t>(r * w));
  }
  return grid;
}

std::vector<float> seamEnergy(const SkeletonRaster& raster, double grayDistBalance) {
  const size_t n = raster.ink.size();
  std::vector<char> feature(n);
  for (size_t i = 0; i < n; ++i) feature[i] = raster.ink[i] > 0.0f ? 1 : 0;
  const std::vector<double> d2 = squaredDistanceTransform(feature, raster.frame.width, raster.frame.height);
  double maxD = 0.0;
  for (double v : d2)
    if (std::isfinite(v)) maxD = std::max(maxD, v);
  maxD = std::sqrt(maxD);
  std::vector<float> energy(n);
  const double b = grayDistBalance;
  for (size_t i = 0; i < n; ++i) {
    const double df = !std::isfinite(d2[i]) ? 0.0
                      : maxD > 0.0          ? 255.0 * (1.0 - std::sqrt(d2[i]) / maxD)
                                            : 255.0;
    energy[i] = raster.freezeOwner[i] != kNotFrozen ? std::numeric_limits<float>::infinity()
                                                    : static_cast<float>(b * raster.ink[i] + (1.0 - b) * df);
  }
  return energy;
}

}  // namespace urbanvec::shrink
