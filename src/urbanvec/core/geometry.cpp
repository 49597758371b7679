#include "urbanvec/core/geometry.hpp"

#include <algorithm>
#include <cmath>

namespace urbanvec {

bool ringContains(const Ring& ring, const Vec2& p) {
  bool inside = false;
  for (size_t i = 0, n = ring.size(); i + 1 < n; ++i)
    if (edgeCrossesRayRight(ring[i], ring[i + 1], p)) inside = !inside;
  return inside;
}

double signedArea(const Ring& ring) {
  double twice = 0.0;
  for (size_t i = 0; i + 1 < ring.size(); ++i) twice += cross(ring[i], ring[i + 1]);
  if (!ring.empty() && ring.front() != ring.back()) twice += cross(ring.back(), ring.front());
  return 0.5 * twice;
}

double area(const Polygon& polygon) {
  double a = std::fabs(signedArea(polygon.outer));
  for (const Ring& hole : polygon.holes) a -= std::fabs(signedArea(hole));
  return a;
}

double area(const MultiPolygon& polygons) {
  double a = 0.0;
  for (const Polygon& p : polygons) a += area(p);
  return a;
}

double length(const LineString& line) {
  double l = 0.0;
  for (size_t i = 0; i + 1 < line.size(); ++i) l += distance(line[i], line[i + 1]);
  return l;
}

LineString headOfLength(const LineString& line, double keep) {
  LineString out{line.front()};
  if (!(keep > 0.0)) return out;
  double at = 0.0;
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    const double len = distance(line[i], line[i + 1]);
    if (at + len >= keep) {
      out.push_back(line[i] + (line[i + 1] - line[i]) * ((keep - at) / std::max(len, 1e-300)));
      return out;
    }
    out.push_back(line[i + 1]);
    at += len;
  }
  return out;
}

LineString densified(const LineString& line, double spacing) {
  if (line.size() < 2) return line;
  LineString dense;
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    const int steps =
        std::max(1, static_cast<int>(std::ceil(distance(line[i], line[i + 1]) / spacing - 1e-9)));
    for (int k = 0; k < steps; ++k) dense.push_back(line[i] + (line[i + 1] - line[i]) * (double(k) / steps));
  }
  dense.push_back(line.back());
  return dense;
}

Ring convexHull(std::vector<Vec2> points) {
  std::sort(points.begin(), points.end(), lexicographicLess);
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  const auto turn = [](const Vec2& o, const Vec2& a, const Vec2& b) { return cross(a - o, b - o); };
  Ring hull(2 * points.size());
  size_t k = 0;
  for (const Vec2& p : points) {
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], p) <= 0.0) --k;
    hull[k++] = p;
  }
  for (size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && turn(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k);  // the upper chain ends on the first point: the ring is closed
  return hull;
}

}  // namespace urbanvec
