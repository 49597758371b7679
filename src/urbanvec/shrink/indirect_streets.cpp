// Step 1 (spec §B.3): add indirect important streets around non-street landmarks and inside bounding
// areas, with the place's weight.
#include "urbanvec/shrink/indirect_streets.hpp"

#include <algorithm>
#include <unordered_map>

#include "urbanvec/shrink/street_graph.hpp"

namespace urbanvec::shrink {

std::vector<StreetImportance> findImportantStreets(const City& city, const std::vector<Place>& places,
                                                   const SelectionOptions& options, IndirectStats* stats) {
  IndirectStats local;
  std::vector<StreetImportance> result(city.streets.size());
  std::unordered_multimap<std::int64_t, int> byId;
  for (size_t w = 0; w < city.streets.size(); ++w) byId.emplace(city.streets[w].osmId, static_cast<int>(w));
  auto mark = [&](int way, int place, bool indirect, int& counter) {
    StreetImportance& s = result[static_cast<size_t>(way)];
    const double w = places[static_cast<size_t>(place)].appearW;
    if (!s.important) ++counter;
    if (!s.important || w > s.appearW || (s.indirect && !indirect && w == s.appearW)) {
      s.appearW = w;
      s.place = place;
      s.indirect = indirect && (!s.important || s.indirect);
    }
    s.important = true;
  };
  // Members first, so a street both named and near a landmark counts as direct.
  for (size_t p = 0; p < places.size(); ++p)
    for (std::int64_t id : places[p].streetIds) {
      auto range = byId.equal_range(id);
      for (auto it = range.first; it != range.second; ++it)
        mark(it->second, static_cast<int>(p), false, local.direct);
    }
  const SegmentGrid grid(city.nodes, city.streets, options.proximityThreshold);
  for (size_t p = 0; p < places.size(); ++p) {
    const Place& place = places[p];
    bool found = place.shapes.empty();
    // Task 1: the nearest street of every node of the landmark (§B.3 1).
    for (const std::vector<int>& shape : place.shapes)
      for (int n : shape) {
        const int way = grid.nearestStreet(city.nodes[static_cast<size_t>(n)].p, options.proximityThreshold);
        if (way < 0) continue;
        found = true;
        mark(way, static_cast<int>(p), true, local.nearest);
      }
    if (!found) ++local.placesWithoutStreet;
    // Task 2: streets with a node inside the bounding polygon (§B.3 2).
    if (place.boundingRing.size() >= 4) {
      Ring ring;
      double minX = 1e300, minY = 1e300, maxX = -1e300, maxY = -1e300;
      for (int n : place.boundingRing) {
        const Vec2 q = city.nodes[static_cast<size_t>(n)].p;
        ring.push_back(q);
        minX = std::min(minX, q.x), maxX = std::max(maxX, q.x), minY = std::min(minY, q.y),
        maxY = std::max(maxY, q.y);
      }
      for (size_t w = 0; w < city.streets.size(); ++w)
        for (int n : city.streets[w].nodes) {
          const Vec2 q = city.nodes[static_cast<size_t>(n)].p;
          if (q.x < minX || q.x > maxX || q.y < minY || q.y > maxY || !insideRing(q, ring)) continue;
          mark(static_cast<int>(w), static_cast<int>(p), true, local.insideBounding);
          break;
        }
    }
  }
  if (stats) *stats = local;
  return result;
}

}  // namespace urbanvec::shrink
