// Islands as suburbs, spec wijgerse-boundary.md §12 item 3 (thesis future work, §7.3).
#include "urbanvec/boundary/islands.hpp"

#include <algorithm>
#include <array>
#include <cstdint>

namespace urbanvec::boundary {

bool insideChain(const std::vector<Pixel>& chain, Pixel p) {
  // Even-odd ray casting towards +x; a pixel on the chain itself counts as inside.
  bool inside = false;
  const size_t n = chain.size();
  for (size_t i = 0, j = n - 1; i < n; j = i++) {
    const Pixel& a = chain[i];
    const Pixel& b = chain[j];
    if (a == p) return true;
    if ((a.y > p.y) != (b.y > p.y)) {
      const double x = a.x + static_cast<double>(p.y - a.y) * (b.x - a.x) / (b.y - a.y);
      if (p.x < x) inside = !inside;
    }
  }
  return inside;
}

std::vector<std::vector<Pixel>> traceIslands(const Grid<std::uint8_t>& mask,
                                             const std::vector<Pixel>& mainChain, double minimumPixels) {
  struct Region {
    Pixel first;  // topmost, then leftmost pixel: its west neighbour is empty
    std::int64_t pixels = 0;
    std::int32_t label = 0;
  };
  Grid<std::int32_t> labels(mask.width, mask.height, 0);
  std::vector<Region> regions;
  std::vector<Pixel> stack;
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x) {
      if (!mask.at(x, y) || labels.at(x, y)) continue;
      Region region{{x, y}, 0, static_cast<std::int32_t>(regions.size() + 1)};
      labels.at(x, y) = region.label;
      stack.push_back({x, y});
      while (!stack.empty()) {
        const Pixel p = stack.back();
        stack.pop_back();
        ++region.pixels;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = p.x + dx;
            const int ny = p.y + dy;
            if (mask.get(nx, ny, 0) && !labels.at(nx, ny)) {
              labels.at(nx, ny) = region.label;
              stack.push_back({nx, ny});
            }
          }
      }
      regions.push_back(region);
    }
  const std::int32_t mainLabel = mainChain.empty() ? 0 : labels.at(mainChain[0].x, mainChain[0].y);
  std::stable_sort(regions.begin(), regions.end(),
                   [](const Region& a, const Region& b) { return a.pixels > b.pixels; });
  std::vector<std::vector<Pixel>> kept;
  for (const Region& region : regions) {
    if (region.label == mainLabel || static_cast<double>(region.pixels) < minimumPixels) continue;
    if (!mainChain.empty() && insideChain(mainChain, region.first)) continue;
    if (std::any_of(kept.begin(), kept.end(),
                    [&](const std::vector<Pixel>& k) { return insideChain(k, region.first); }))
      continue;
    kept.push_back(traceContour(mask, region.first));
  }
  return kept;
}

}  // namespace urbanvec::boundary
