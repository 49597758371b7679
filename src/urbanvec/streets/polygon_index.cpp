// Slab-bucketed polygon edges for point-in-polygon, crossing and distance tests (see the header).
#include "urbanvec/streets/polygon_index.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace urbanvec::streets {

PolygonIndex::PolygonIndex(const MultiPolygon& polygons, int slabs) {
  double minY = std::numeric_limits<double>::infinity(), maxY = -minY;
  minX_ = minY, maxX_ = -minY;
  auto addRing = [&](const Ring& ring) {
    for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
      if (ring[i] == ring[i + 1]) continue;
      edges_.push_back({ring[i], ring[i + 1]});
      minY = std::min(minY, ring[i].y), maxY = std::max(maxY, ring[i].y);
      minX_ = std::min(minX_, ring[i].x), maxX_ = std::max(maxX_, ring[i].x);
    }
    // An unclosed ring still closes.
    if (ring.size() >= 3 && ring.front() != ring.back()) edges_.push_back({ring.back(), ring.front()});
  };
  for (const Polygon& p : polygons) {
    addRing(p.outer);
    for (const Ring& h : p.holes) addRing(h);
  }
  if (edges_.empty()) return;
  const int n =
      slabs > 0 ? slabs : std::max(1, static_cast<int>(std::sqrt(static_cast<double>(edges_.size()))));
  minY_ = minY;
  slabHeight_ = std::max((maxY - minY) / n, 1e-9);
  slabs_.assign(static_cast<std::size_t>(n), {});
  for (int e = 0; e < static_cast<int>(edges_.size()); ++e) {
    const Edge& ed = edges_[static_cast<std::size_t>(e)];
    const int s0 = slabOf(std::min(ed.a.y, ed.b.y)), s1 = slabOf(std::max(ed.a.y, ed.b.y));
    for (int s = s0; s <= s1; ++s) slabs_[static_cast<std::size_t>(s)].push_back(e);
  }
}

int PolygonIndex::slabOf(double y) const {
  const int s = static_cast<int>(std::floor((y - minY_) / slabHeight_));
  return std::clamp(s, 0, static_cast<int>(slabs_.size()) - 1);
}

bool PolygonIndex::contains(const Vec2& p) const {
  if (edges_.empty() || p.x < minX_ || p.x > maxX_ || p.y < minY_ ||
      p.y > minY_ + slabHeight_ * static_cast<double>(slabs_.size()))
    return false;
  bool inside = false;
  for (int e : slabs_[static_cast<std::size_t>(slabOf(p.y))]) {
    const Edge& ed = edges_[static_cast<std::size_t>(e)];
    if ((ed.a.y > p.y) != (ed.b.y > p.y)) {
      const double x = ed.a.x + (p.y - ed.a.y) * (ed.b.x - ed.a.x) / (ed.b.y - ed.a.y);
      if (x > p.x) inside = !inside;
    }
  }
  return inside;
}

double PolygonIndex::firstCrossing(const Vec2& a, const Vec2& b) const {
  double best = 2.0;
  if (edges_.empty()) return best;
  const Vec2 d = b - a;
  const int s0 = slabOf(std::min(a.y, b.y)), s1 = slabOf(std::max(a.y, b.y));
  for (int s = s0; s <= s1; ++s)
    for (int e : slabs_[static_cast<std::size_t>(s)]) {
      const Edge& ed = edges_[static_cast<std::size_t>(e)];
      const Vec2 f = ed.b - ed.a;
      const double den = cross(d, f);
      if (den == 0.0) continue;
      const double t = cross(ed.a - a, f) / den;
      const double u = cross(ed.a - a, d) / den;
      if (t >= 0.0 && t <= 1.0 && u >= 0.0 && u <= 1.0) best = std::min(best, t);
    }
  return best;
}

double PolygonIndex::distanceToEdge(const Vec2& p, double maxDistance) const {
  double best = maxDistance;
  if (edges_.empty()) return best;
  const int s0 = slabOf(p.y - maxDistance), s1 = slabOf(p.y + maxDistance);
  for (int s = s0; s <= s1; ++s)
    for (int e : slabs_[static_cast<std::size_t>(s)]) {
      const Edge& ed = edges_[static_cast<std::size_t>(e)];
      best = std::min(best, distanceToSegment(p, ed.a, ed.b));
    }
  return best;
}

}  // namespace urbanvec::streets
