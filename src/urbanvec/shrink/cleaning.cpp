// Step 0 (spec §B.2): remove empty ways and the segments outside the download bounds.
#include "urbanvec/shrink/cleaning.hpp"

namespace urbanvec::shrink {

CleaningStats cleanCity(City& city, const CleaningOptions& options) {
  CleaningStats stats;
  stats.waysIn = static_cast<int>(city.streets.size());
  std::vector<CityWay> kept;
  kept.reserve(city.streets.size());
  std::vector<char> counted(city.nodes.size(), 0);
  for (CityWay& way : city.streets) {
    CityWay piece{way.osmId, {}, way.highway, way.name};
    auto flush = [&]() {
      if (piece.nodes.size() >= 2)
        kept.push_back(piece);
      else if (piece.nodes.size() == 1)
        ++stats.emptyWays;
      piece.nodes.clear();
    };
    for (int n : way.nodes) {
      if (options.removeOutsideBounds && !city.nodes[static_cast<size_t>(n)].inBounds) {
        if (!counted[static_cast<size_t>(n)]) counted[static_cast<size_t>(n)] = 1, ++stats.nodesOutsideBounds;
        flush();
        continue;
      }
      if (!piece.nodes.empty() && piece.nodes.back() == n) continue;
      piece.nodes.push_back(n);
    }
    if (way.nodes.empty()) ++stats.emptyWays;
    flush();
  }
  city.streets = std::move(kept);
  stats.waysOut = static_cast<int>(city.streets.size());
  return stats;
}

}  // namespace urbanvec::shrink
