// Step 2 (spec §B.4): street importance weights and selection by the shrinking factor shF.
#include "urbanvec/shrink/street_selection.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace urbanvec::shrink {

double streetTypeWeight(const std::string& highway, const SelectionOptions& options) {
  auto it = options.highwayWeights.find(highway);
  return (it != options.highwayWeights.end() ? it->second : options.otherHighwayWeight) / 10.0;
}

Selection selectStreets(const City& city, const StreetGraph& graph,
                        const std::vector<StreetImportance>& importance, const SelectionOptions& options) {
  Selection sel;
  const size_t n = city.streets.size();
  sel.scores.resize(n);
  sel.selected.assign(n, 0);
  int maxIntersections = 0;
  double minLength = 0.0, maxLength = 0.0;
  std::vector<int> seen(city.nodes.size(), -1);
  for (size_t w = 0; w < n; ++w) {
    StreetScore& s = sel.scores[w];
    const std::vector<int>& ns = city.streets[w].nodes;
    for (size_t i = 0; i < ns.size(); ++i) {
      if (i > 0)
        s.length +=
            distance(city.nodes[static_cast<size_t>(ns[i - 1])].p, city.nodes[static_cast<size_t>(ns[i])].p);
      const size_t node = static_cast<size_t>(ns[i]);
      if (seen[node] == static_cast<int>(w)) continue;
      seen[node] = static_cast<int>(w);
      if (graph.wayCount[node] >= 2) ++s.intersections;
    }
    maxIntersections = std::max(maxIntersections, s.intersections);
    minLength = w == 0 ? s.length : std::min(minLength, s.length);
    maxLength = w == 0 ? s.length : std::max(maxLength, s.length);
  }
  for (size_t w = 0; w < n; ++w) {
    StreetScore& s = sel.scores[w];
    if (importance[w].important) {
      s.impW = options.importantBase + (1.0 - options.importantBase) * importance[w].appearW;
      ++sel.importantCount;
    } else {
      s.impW = streetTypeWeight(city.streets[w].highway, options);
      if (maxIntersections > 0) s.impW += options.intersectionFactor * s.intersections / maxIntersections;
      if (maxLength > minLength)
        s.impW += options.lengthFactor * (s.length - minLength) / (maxLength - minLength);
    }
    s.impD = s.length > 0.0 ? s.impW / s.length : s.impW;
  }
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const double wa = sel.scores[static_cast<size_t>(a)].impW, wb = sel.scores[static_cast<size_t>(b)].impW;
    if (wa != wb) return wa > wb;
    return importance[static_cast<size_t>(a)].important > importance[static_cast<size_t>(b)].important;
  });
  const auto keep = static_cast<size_t>(std::lround(options.shrinkFactor * static_cast<double>(n)));
  for (size_t i = 0; i < keep && i < n; ++i) {
    sel.selected[static_cast<size_t>(order[i])] = 1;
    ++sel.selectedCount;
    if (importance[static_cast<size_t>(order[i])].important) ++sel.importantSelected;
  }
  return sel;
}

}  // namespace urbanvec::shrink
