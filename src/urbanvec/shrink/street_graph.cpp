// CityLib street-network structures (spec §C.2 directGraph and intersectionAccelerator, §C.3 proximity
// accelerator).
#include "urbanvec/shrink/street_graph.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace urbanvec::shrink {

StreetGraph buildStreetGraph(const std::vector<CityNode>& nodes, const std::vector<CityWay>& streets) {
  StreetGraph g;
  g.graphNode.assign(nodes.size(), -1);
  g.wayCount.assign(nodes.size(), 0);
  std::vector<int> lastWay(nodes.size(), -1);
  for (size_t w = 0; w < streets.size(); ++w)
    for (int n : streets[w].nodes) {
      if (g.graphNode[static_cast<size_t>(n)] < 0) {
        g.graphNode[static_cast<size_t>(n)] = g.graph.addNode(nodes[static_cast<size_t>(n)].p);
        g.cityNode.push_back(n);
      }
      if (lastWay[static_cast<size_t>(n)] != static_cast<int>(w)) {
        lastWay[static_cast<size_t>(n)] = static_cast<int>(w);
        ++g.wayCount[static_cast<size_t>(n)];
      }
    }
  for (size_t w = 0; w < streets.size(); ++w) {
    const std::vector<int>& ns = streets[w].nodes;
    for (size_t i = 1; i < ns.size(); ++i) {
      const int a = g.graphNode[static_cast<size_t>(ns[i - 1])], b = g.graphNode[static_cast<size_t>(ns[i])];
      if (a == b) continue;
      g.graph.addEdge(a, b);
      g.edgeWay.push_back(static_cast<int>(w));
    }
  }
  return g;
}

SegmentGrid::SegmentGrid(const std::vector<CityNode>& nodes, const std::vector<CityWay>& streets,
                         double cellSize) {
  double minX = std::numeric_limits<double>::infinity(), minY = minX, maxX = -minX, maxY = -minX;
  for (size_t w = 0; w < streets.size(); ++w)
    for (size_t i = 1; i < streets[w].nodes.size(); ++i) {
      const Vec2 a = nodes[static_cast<size_t>(streets[w].nodes[i - 1])].p;
      const Vec2 b = nodes[static_cast<size_t>(streets[w].nodes[i])].p;
      segments_.push_back({a, b, static_cast<int>(w)});
      minX = std::min({minX, a.x, b.x}), maxX = std::max({maxX, a.x, b.x});
      minY = std::min({minY, a.y, b.y}), maxY = std::max({maxY, a.y, b.y});
    }
  if (segments_.empty()) return;
  origin_ = {minX, minY};
  // Keep the grid to a few million cells whatever the threshold.
  cell_ = std::max({cellSize, (maxX - minX) / 2000.0, (maxY - minY) / 2000.0, 1e-9});
  nx_ = static_cast<int>((maxX - minX) / cell_) + 1;
  ny_ = static_cast<int>((maxY - minY) / cell_) + 1;
  cells_.assign(static_cast<size_t>(nx_) * static_cast<size_t>(ny_), {});
  for (size_t s = 0; s < segments_.size(); ++s) {
    const Segment& seg = segments_[s];
    for (int y = cellY(std::min(seg.a.y, seg.b.y)); y <= cellY(std::max(seg.a.y, seg.b.y)); ++y)
      for (int x = cellX(std::min(seg.a.x, seg.b.x)); x <= cellX(std::max(seg.a.x, seg.b.x)); ++x)
        cells_[static_cast<size_t>(y) * static_cast<size_t>(nx_) + static_cast<size_t>(x)].push_back(
            static_cast<int>(s));
  }
}

int SegmentGrid::cellX(double x) const {
  return std::clamp(static_cast<int>(std::floor((x - origin_.x) / cell_)), 0, nx_ - 1);
}
int SegmentGrid::cellY(double y) const {
  return std::clamp(static_cast<int>(std::floor((y - origin_.y) / cell_)), 0, ny_ - 1);
}

int SegmentGrid::nearestStreet(const Vec2& p, double maxDistance, double* distanceOut) const {
  if (segments_.empty()) return -1;
  int best = -1;
  double bestDistance = maxDistance;
  for (int y = cellY(p.y - maxDistance); y <= cellY(p.y + maxDistance); ++y)
    for (int x = cellX(p.x - maxDistance); x <= cellX(p.x + maxDistance); ++x)
      for (int s : cells_[static_cast<size_t>(y) * static_cast<size_t>(nx_) + static_cast<size_t>(x)]) {
        const Segment& seg = segments_[static_cast<size_t>(s)];
        const double d = distanceToSegment(p, seg.a, seg.b);
        if (d < bestDistance || (d == bestDistance && best >= 0 && seg.way < best) ||
            (d <= bestDistance && best < 0)) {
          bestDistance = d;
          best = seg.way;
        }
      }
  if (distanceOut) *distanceOut = bestDistance;
  return best;
}

bool insideRing(const Vec2& p, const Ring& ring) {
  bool inside = false;
  if (ring.size() < 3) return false;
  for (size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const Vec2& a = ring[i];
    const Vec2& b = ring[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) inside = !inside;
  }
  return inside;
}

}  // namespace urbanvec::shrink
